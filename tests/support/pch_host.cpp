// SPDX-License-Identifier: Apache-2.0
// The program that owns the test programs' precompiled header (tests/CMakeLists.txt, ARTCAM_PCH);
// it is never run.
int main() { return 0; }
