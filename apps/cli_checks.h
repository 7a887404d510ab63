// Checks of the `armour` command's options and the one error line of a bad
// command line.
//
// Description
//     CLI11 reads "1.5" given to an integer option as a conversion error with
//     a message of its own, lets "-1" wrap to 2^64-1 in an unsigned one and
//     "inf" or "nan" through to a number. The checks here run on the text
//     before CLI11 converts it and give the reason; CLI11 prefixes the
//     option's name: "--spheres: 'abc' is not an integer". Every parse error
//     then becomes one line `armour: error: ...` and exit status 2, as bad
//     input does (cli.h); --help prints help and exits 0.
//
// Usage
//     app.add_option("--np", np, "MPI ranks")->check(integer_at_least(1));
//     add_type_checks(app);                  // after every option is declared
//     try { app.parse(argc, argv); }
//     catch (const CLI::ParseError &e) { return parse_error_exit(app, e); }
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace armour {

// An integer >= lo: "'abc' is not an integer", "must be >= 1 (got 0)".
CLI::Validator integer_at_least(long lo);
// A finite number > lo, in `unit` (SI): "'x' is not a number", "must be > 0 s (got -1)".
CLI::Validator number_above(double lo, const std::string &unit);

// Adds to every integer, unsigned and floating-point option of `app` and its
// subcommands the check that its text is one (finite, in range). Call it
// after the options' own checks: those run first and check the type too.
void add_type_checks(CLI::App &app);

// Prints help (--help: status 0) or the parse error as one line
// `armour: error: ...` on stderr (status 2); returns the exit status.
int parse_error_exit(CLI::App &app, const CLI::ParseError &error);

} // namespace armour
