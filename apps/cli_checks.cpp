#include "cli_checks.h"

#include "scene_keys.h" // number_text

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>

namespace armour {

namespace {

bool all_digits(const std::string &s, std::size_t from) {
    return s.size() > from && s.find_first_not_of("0123456789", from) == std::string::npos;
}

// A decimal integer within [lo, hi] (no hex, no exponent, no spaces).
std::optional<long long> integer_of(const std::string &text, long long lo, long long hi) {
    if (!all_digits(text, text[0] == '-' || text[0] == '+' ? 1 : 0))
        return std::nullopt;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), nullptr, 10);
    if (errno == ERANGE || v < lo || v > hi)
        return std::nullopt;
    return v;
}

// A finite decimal number (strtod would also take hex, "inf" and "nan").
std::optional<double> number_of(const std::string &text) {
    if (text.empty() || text.find_first_of("xXnN") != std::string::npos ||
        std::isspace(static_cast<unsigned char>(text[0])))
        return std::nullopt;
    char *end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (*end != '\0' || !std::isfinite(v))
        return std::nullopt;
    return v;
}

std::string in_quotes(const std::string &text) {
    return "'" + text + "'";
}

std::string int_reason(const std::string &text) {
    if (all_digits(text, text[0] == '-' || text[0] == '+' ? 1 : 0))
        return in_quotes(text) + " is out of range";
    return in_quotes(text) + " is not an integer";
}

CLI::Validator int_check() {
    return CLI::Validator(
        [](std::string &text) {
            return integer_of(text, INT_MIN, INT_MAX) ? std::string() : int_reason(text);
        },
        "");
}

// Seeds: 0 .. 2^64-1 (CLI11 would wrap "-1").
CLI::Validator uint_check() {
    return CLI::Validator(
        [](std::string &text) {
            if (all_digits(text, text[0] == '+' ? 1 : 0)) {
                errno = 0;
                std::strtoull(text.c_str(), nullptr, 10);
                return errno == ERANGE ? in_quotes(text) + " is out of range" : std::string();
            }
            return in_quotes(text) + " is not an integer >= 0";
        },
        "");
}

std::string number_reason(const std::string &text) {
    const bool finite = std::isfinite(std::strtod(text.c_str(), nullptr));
    return in_quotes(text) + (finite ? " is not a number" : " is not a finite number");
}

CLI::Validator float_check() {
    return CLI::Validator(
        [](std::string &text) { return number_of(text) ? std::string() : number_reason(text); }, "");
}

// The option an ExtrasError is about and the command it was given to.
std::string extra_argument_line(CLI::App &app) {
    CLI::App *where = &app;
    for (CLI::App *sub : app.get_subcommands())
        if (!sub->remaining().empty())
            where = sub;
    const std::vector<std::string> extras = where->remaining();
    const std::string arg = extras.empty() ? std::string("?") : extras.front();
    const std::string help = where == &app ? "armour --help" : "armour " + where->get_name() + " --help";
    if (arg.size() > 1 && arg[0] == '-')
        return arg + ": unknown option (" + help + " lists them)";
    return in_quotes(arg) + ": unexpected argument (" + help + ")";
}

std::string command_list(const CLI::App &app) {
    std::string names;
    for (const CLI::App *sub : app.get_subcommands([](const CLI::App *) { return true; }))
        names += (names.empty() ? "" : ", ") + sub->get_name();
    return names;
}

std::string one_line(std::string text) {
    for (char &c : text)
        if (c == '\n')
            c = ' ';
    return text;
}

} // namespace

CLI::Validator integer_at_least(long lo) {
    return CLI::Validator(
        [lo](std::string &text) {
            const std::optional<long long> v = integer_of(text, INT_MIN, INT_MAX);
            if (!v)
                return int_reason(text);
            return *v >= lo ? std::string() : "must be >= " + std::to_string(lo) + " (got " + text + ")";
        },
        ">=" + std::to_string(lo));
}

CLI::Validator number_above(double lo, const std::string &unit) {
    const std::string bound = "> " + number_text(lo) + (unit.empty() ? "" : " " + unit);
    return CLI::Validator(
        [lo, bound](std::string &text) {
            const std::optional<double> v = number_of(text);
            if (!v)
                return number_reason(text);
            return *v > lo ? std::string() : "must be " + bound + " (got " + text + ")";
        },
        ">" + number_text(lo));
}

void add_type_checks(CLI::App &app) {
    for (CLI::Option *option : app.get_options()) {
        const std::string type = option->get_type_name();
        if (type.rfind("INT", 0) == 0)
            option->check(int_check());
        else if (type.rfind("UINT", 0) == 0)
            option->check(uint_check());
        else if (type.rfind("FLOAT", 0) == 0)
            option->check(float_check());
    }
    for (CLI::App *sub : app.get_subcommands([](const CLI::App *) { return true; }))
        add_type_checks(*sub);
}

int parse_error_exit(CLI::App &app, const CLI::ParseError &error) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
        return app.exit(error); // --help: prints it, status 0
    std::string line = one_line(error.what());
    if (dynamic_cast<const CLI::ExtrasError *>(&error)) {
        line = extra_argument_line(app);
    } else if (dynamic_cast<const CLI::RequiredError *>(&error) && line == "A subcommand is required") {
        const std::vector<std::string> given = app.remaining();
        if (!given.empty() && given.front().size() > 1 && given.front()[0] == '-')
            line = extra_argument_line(app); // `armour --bogus`
        else
            line =
                (given.empty() ? "a command is required" : in_quotes(given.front()) + " is not a command") +
                ", one of: " + command_list(app) + " (armour --help)";
    } else if (dynamic_cast<const CLI::ArgumentMismatch *>(&error) &&
               line.find(" missing") != std::string::npos) {
        line = line.substr(0, line.find(": ")) + ": needs a value";
    }
    std::cerr << "armour: error: " << line << '\n';
    return 2;
}

} // namespace armour
