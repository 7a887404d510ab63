// libFuzzer target: the STL reader, ASCII and binary (docs/fuzzing.md).
#include "fuzz_input.h"
#include "stl_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_input::refused_or_read(data, size, ".stl", [](const std::string &path) {
        const armour::TriangleMesh mesh = armour::read_stl(path);
        // What the reader promises: every triangle indexes its vertices.
        for (const auto &t : mesh.triangles)
            for (const int v : t)
                if (v < 0 || static_cast<size_t>(v) >= mesh.vertices.size())
                    __builtin_trap();
    });
}
