# SPDX-License-Identifier: Apache-2.0
# Installs what a desktop needs besides the two programs (desktop entry, icons, AppStream
# metainfo, MIME types, manual pages, shell completions, Debian's copyright and changelog) and
# configures CPack's Debian package, so that
# `cmake --install` and `cpack -G DEB` lay down the same files (packaging/build-deb.sh).
# Relative destinations: cpack installs under /usr, `cmake --install` under CMAKE_INSTALL_PREFIX.
include(GNUInstallDirs)

set(ARTCAM_APP_ID org.artcam.Studio)  # reverse-DNS id shared by the .desktop, icon and metainfo
set(_artcam_desktop_dir ${PROJECT_SOURCE_DIR}/packaging/desktop)

# The MIME types describe the CLI's files too, so they install with either front end.
install(FILES ${_artcam_desktop_dir}/${ARTCAM_APP_ID}.mime.xml
  DESTINATION ${CMAKE_INSTALL_DATADIR}/mime/packages RENAME ${ARTCAM_APP_ID}.xml)

set(_artcam_man_pages artcam.1)
if(ARTCAM_BUILD_GUI)
  list(APPEND _artcam_man_pages artcam-studio.1)
  install(FILES ${_artcam_desktop_dir}/${ARTCAM_APP_ID}.desktop
    DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
  install(FILES ${_artcam_desktop_dir}/${ARTCAM_APP_ID}.metainfo.xml
    DESTINATION ${CMAKE_INSTALL_DATADIR}/metainfo)
  install(FILES ${_artcam_desktop_dir}/icons/${ARTCAM_APP_ID}.svg
    DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
  foreach(_size 16 24 32 48 64 128 256)
    install(FILES ${_artcam_desktop_dir}/icons/${ARTCAM_APP_ID}-${_size}.png
      DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/${_size}x${_size}/apps
      RENAME ${ARTCAM_APP_ID}.png)
  endforeach()
endif()

# The bundled sample (README, "Install"): a photo (CC0, resources/README.md), a camera, its
# matches and a project that opens the photo by its relative path.
install(FILES ${PROJECT_SOURCE_DIR}/resources/coffee.png ${PROJECT_SOURCE_DIR}/resources/sample.artcam
  ${PROJECT_SOURCE_DIR}/resources/sample.artcamproj ${PROJECT_SOURCE_DIR}/resources/sample-matches.csv
  DESTINATION ${CMAKE_INSTALL_DATADIR}/artcam-studio/examples)

# Shell completions, where bash-completion, zsh and fish look for them (loaded on first use of artcam).
install(FILES ${PROJECT_SOURCE_DIR}/packaging/completions/artcam.bash
  DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME artcam)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/completions/_artcam
  DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/completions/artcam.fish
  DESTINATION ${CMAKE_INSTALL_DATADIR}/fish/vendor_completions.d)

# Manual pages, compressed as Debian policy asks (gzip -9n: no name or time stamp inside, so
# the package is reproducible).
find_program(ARTCAM_GZIP gzip REQUIRED)
set(_artcam_man_outputs "")
foreach(_page IN LISTS _artcam_man_pages)
  set(_src ${PROJECT_SOURCE_DIR}/docs/man/${_page})
  set(_copy ${PROJECT_BINARY_DIR}/man/${_page})
  add_custom_command(OUTPUT ${_copy}.gz
    COMMAND ${CMAKE_COMMAND} -E copy ${_src} ${_copy}
    COMMAND ${ARTCAM_GZIP} -9nf ${_copy}
    DEPENDS ${_src} VERBATIM)
  list(APPEND _artcam_man_outputs ${_copy}.gz)
endforeach()
add_custom_target(artcam_man ALL DEPENDS ${_artcam_man_outputs})
install(FILES ${_artcam_man_outputs} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

# Debian's per-package documents: the machine-readable copyright file (DEP-5: Apache-2.0 for
# the project, CC0-1.0 for the sample photo) and the packaging changelog, gzip -9n like the
# manual pages. The package revision is the changelog's: its first entry must name
# <PROJECT_VERSION>-<CPACK_DEBIAN_PACKAGE_RELEASE>, checked here so a version bump cannot leave
# it behind.
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(_artcam_doc_dir ${CMAKE_INSTALL_DATADIR}/doc/artcam-studio)
set(_artcam_debian_dir ${PROJECT_SOURCE_DIR}/packaging/debian)
file(STRINGS ${_artcam_debian_dir}/changelog _artcam_changelog_top LIMIT_COUNT 1)
set(_artcam_deb_version ${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE})
if(NOT _artcam_changelog_top MATCHES "^artcam-studio \\(${_artcam_deb_version}\\) ")
  message(FATAL_ERROR "packaging/debian/changelog: the first entry is \"${_artcam_changelog_top}\"; "
                      "the package is artcam-studio ${_artcam_deb_version}: add an entry for it")
endif()
install(FILES ${_artcam_debian_dir}/copyright DESTINATION ${_artcam_doc_dir})
set(_artcam_changelog ${PROJECT_BINARY_DIR}/debian/changelog.Debian)
add_custom_command(OUTPUT ${_artcam_changelog}.gz
  COMMAND ${CMAKE_COMMAND} -E copy ${_artcam_debian_dir}/changelog ${_artcam_changelog}
  COMMAND ${ARTCAM_GZIP} -9nf ${_artcam_changelog}
  DEPENDS ${_artcam_debian_dir}/changelog VERBATIM)
add_custom_target(artcam_debian_changelog ALL DEPENDS ${_artcam_changelog}.gz)
install(FILES ${_artcam_changelog}.gz DESTINATION ${_artcam_doc_dir})

# The Debian package: one package with both programs; dpkg-shlibdeps derives Depends from the
# installed binaries' shared libraries (Qt, OpenImageIO, libstdc++ ...).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME artcam-studio)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "ARTcam Studio")
set(CPACK_PACKAGE_CONTACT "ARTcam Studio maintainers <maintainers@artcam.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "fit rational tensor cameras and warp photographs through them")
# Lines under 80 columns (lintian's extended-description-line-too-long).
set(CPACK_PACKAGE_DESCRIPTION
  "ARTcam Studio fits Attributed Rational Tensor cameras (every output
coordinate a ratio of quadratic forms of the input) to point matches and
warps photographs through them: lens distortion, reflections, refractions
and artistic deformations. The package holds the artcam-studio GUI, the
artcam command-line tool and the artcam Python 3 module.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)  # RelWithDebInfo binaries carry debug info the package does not need
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # artcam-studio_<version>-<release>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The engine and its image module are private libraries in <libdir>/artcam (core/CMakeLists.txt):
# dpkg-shlibdeps is pointed at their build copies (-l) rather than asking which package has them.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${PROJECT_BINARY_DIR}/lib")
# lensfun's database is data, not a shared library, so shlibdeps cannot find it.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "liblensfun-data-v1")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "qt6-wayland")
if(ARTCAM_BUILD_PYTHON)
  # `import artcam` is built for Debian 12's Python 3.11 ABI and hands out numpy arrays;
  # artcam.dask runs on dask.distributed where it is installed.
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
    ", python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
  string(APPEND CPACK_DEBIAN_PACKAGE_SUGGESTS ", python3-distributed")
endif()
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)
include(CPack)

# Cheap checks of what this file installs (the .deb itself is built by packaging/build-deb.sh,
# not by CI). The validators are required, not optional: packaging/install-deps.sh installs them.
if(ARTCAM_BUILD_TESTS)
  add_test(NAME packaging/desktop_files
    COMMAND bash ${PROJECT_SOURCE_DIR}/packaging/check-desktop-files.sh)
  add_test(NAME packaging/man_pages COMMAND bash ${PROJECT_SOURCE_DIR}/packaging/check-man-pages.sh)
  add_test(NAME packaging/spdx COMMAND bash ${PROJECT_SOURCE_DIR}/packaging/check-spdx.sh)
  add_test(NAME app/cli_version COMMAND artcam --version)
  set_tests_properties(app/cli_version PROPERTIES
    PASS_REGULAR_EXPRESSION "^artcam ${PROJECT_VERSION}\n$")
  if(TARGET artcam-studio)
    # The version the studio reports is the project's; --help lists its options. No display at
    # all (xcb without DISPLAY would abort): both must answer before Qt opens one.
    add_test(NAME app/studio_version COMMAND artcam-studio --version)
    add_test(NAME app/studio_help COMMAND artcam-studio --help)
    set_tests_properties(app/studio_version app/studio_help PROPERTIES
      ENVIRONMENT "QT_QPA_PLATFORM=xcb;DISPLAY=;WAYLAND_DISPLAY=")
    set_tests_properties(app/studio_version PROPERTIES
      PASS_REGULAR_EXPRESSION "^ARTcam Studio ${PROJECT_VERSION}\n$")
    set_tests_properties(app/studio_help PROPERTIES
      PASS_REGULAR_EXPRESSION "--version.*\\.artcamproj")
  endif()
endif()
