// The collide command as a function: main() calls it, and so does the command's fuzzer
// (fuzz/cli_fuzzer.cpp), which drives the whole command line in-process.
#pragma once

// Parses the arguments (argv[0] is the program's name), runs the subcommand and returns the exit
// code: 0, 1 for an error (printed as "collide: message"), CLI11's code for a bad command line, or
// kExitFaults (commands.h). Output goes to stdout and stderr; files only where the arguments say.
int runCollide(int argc, const char* const* argv);
