// SPDX-License-Identifier: Apache-2.0
// Ctrl-C and kill for long CLI jobs, which stop without leaving partial
// files. SIGINT/SIGTERM handlers are installed once for every command (dispatch.cpp):
// - by default a signal unlinks the temporaries of saves in flight (core/io/atomic_file.h;
//   finished outputs were renamed into place and stay) and exits with 128 + signal number
//   (130 for SIGINT) at once;
// - while a CooperativeInterrupt is alive (warp, batch) the first signal only raises a flag
//   that the command polls between tiles, bands of rows and files: it cancels the render or
//   save in progress (the atomic writer removes its temporary), keeps what is finished, prints
//   a summary and returns interruptExitCode(). A second signal exits at once as above.
#pragma once

#include <functional>

namespace artcam::cli {

void installInterruptHandlers();

class CooperativeInterrupt {
 public:
  CooperativeInterrupt();
  ~CooperativeInterrupt();
  CooperativeInterrupt(const CooperativeInterrupt&) = delete;
  CooperativeInterrupt& operator=(const CooperativeInterrupt&) = delete;
};

bool interruptRequested();
// 128 + the signal's number (130 for SIGINT, 143 for SIGTERM); 1 when no signal came.
int interruptExitCode();

// A progress callback for core's readers, renderers and writers: passes the fraction on to
// `report` (may be empty) and returns false (cancel) once a signal came.
std::function<bool(double)> cancelOnInterrupt(std::function<void(double)> report = {});

}  // namespace artcam::cli
