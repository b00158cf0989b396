// SPDX-License-Identifier: Apache-2.0
// artcam: the command line of ARTcam Studio. Subcommands live in their own files.
#include "app/cli/commands.h"

int main(int argc, char** argv) { return artcam::cli::run(argc, argv); }
