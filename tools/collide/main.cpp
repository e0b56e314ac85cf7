// The collide command: everything but the entry point is in the collide_cli library
// (command_line.cpp), so that the fuzzer can call it too.
#include "command_line.h"

int main(int argc, char** argv) { return runCollide(argc, argv); }
