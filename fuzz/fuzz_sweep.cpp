// libFuzzer target: the sweep file reader of `armour sweep` (docs/fuzzing.md).
#include "fuzz_input.h"
#include "sweep_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_input::refused_or_read(data, size, ".toml",
                                       [](const std::string &path) { (void)armour::read_sweep_file(path); });
}
