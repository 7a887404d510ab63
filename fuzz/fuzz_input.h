// What every fuzz target shares: the readers take a path, so each input is
// written to a file of this process first.
//
// Description
//     A reader may refuse an input only with armour::InputError (one clear
//     line for the user); any other exception escapes the target and
//     libFuzzer reports it as a crash, like an overrun AddressSanitizer sees
//     or a hang past -timeout.
//
// Usage
//     extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
//         return fuzz_input::refused_or_read(data, size, ".toml", [](const std::string &path) { ... });
//     }
#pragma once

#include "input_error.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace fuzz_input {

inline std::string file_of(const uint8_t *data, size_t size, const std::string &suffix) {
    static const std::string path =
        (std::filesystem::temp_directory_path() / ("armour_fuzz_" + std::to_string(::getpid()) + suffix))
            .string();
    std::FILE *file = std::fopen(path.c_str(), "wb");
    if (!file || std::fwrite(data, 1, size, file) != size || std::fclose(file) != 0)
        __builtin_trap(); // the fuzzer's own file: not the reader's fault, but nothing can be tested
    return path;
}

template <class Read>
int refused_or_read(const uint8_t *data, size_t size, const std::string &suffix, Read read) {
    const std::string path = file_of(data, size, suffix);
    try {
        read(path);
    } catch (const armour::InputError &) {
        // A refusal with a message is a correct answer to a bad file.
    }
    return 0;
}

} // namespace fuzz_input
