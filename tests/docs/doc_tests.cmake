# SPDX-License-Identifier: Apache-2.0
# docs/code_blocks: every fenced code block of README.md and docs/ (user-guide, performance,
# robustness) is run against the built artcam or checked; tests/docs/run_doc_blocks.py says what
# each fence language gets. Included at the end of tests/CMakeLists.txt.
if(TARGET artcam)
  find_package(Python3 COMPONENTS Interpreter)
  # Debian's /usr/bin/python3 first: a python3 earlier on PATH (a pyenv shim, a venv) may lack
  # the modules the README's Python block imports (python3-numpy, python3-openimageio).
  if(EXISTS /usr/bin/python3)
    set(_artcam_docs_python /usr/bin/python3)
  elseif(Python3_Interpreter_FOUND)
    set(_artcam_docs_python ${Python3_EXECUTABLE})
  endif()
  if(_artcam_docs_python)
    add_test(NAME docs/code_blocks
             COMMAND ${_artcam_docs_python} ${CMAKE_CURRENT_LIST_DIR}/run_doc_blocks.py
                     ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:artcam>)
    set_tests_properties(docs/code_blocks PROPERTIES TIMEOUT 600)
  else()
    message(WARNING "docs/code_blocks needs python3")
  endif()
endif()
