// Entry point of the `armour` command, callable in-process (tests use it).
#pragma once

namespace armour {

// Parses the command line, runs the subcommand, returns the exit status:
// 0 success, 1 command-line syntax error, 2 bad input or an unreachable
// request such as a tolerance no allowed clump meets (one line on stderr,
// nothing written), 4 an internal error.
int armour_main(int argc, const char *const *argv);

} // namespace armour
