// Entry point of the `armour` command, callable in-process (tests use it).
#pragma once

namespace armour {

// Parses the command line, runs the subcommand, returns the exit status:
// 0 success (and --help), 2 bad input, the command line's own errors
// included (an unknown option, a missing value, "abc" for a number), or an
// unreachable request such as a tolerance no allowed clump meets (one line
// `armour: error: ...` on stderr, nothing written), 4 an internal error;
// `armour sweep` returns 1 when a case failed or did not finish.
int armour_main(int argc, const char *const *argv);

} // namespace armour
