// scene_keys: the scene key reference from the key table (scene_keys.h).
//
// Usage
//     scene_keys --markdown              every section's table, to stdout
//     scene_keys --update docs/scenes.md regenerate the marked blocks in place
#include "input_error.h"
#include "scene_keys.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace {

int update(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw armour::InputError(path + ": cannot read");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string updated = armour::with_generated_key_reference(text.str());
    if (updated == text.str())
        return 0;
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary);
        out << updated;
        if (!out)
            throw armour::InputError(temporary + ": cannot write");
    }
    std::filesystem::rename(temporary, path);
    std::cout << path << ": key reference regenerated\n";
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    const std::string option = argc > 1 ? argv[1] : "";
    try {
        if (option == "--markdown" && argc == 2) {
            for (const auto &section : armour::scene_sections()) {
                const std::string name = section.name;
                std::cout << "## " << (name.empty() ? "Top level" : "`" + name + "`") << "\n\n"
                          << armour::scene_keys_markdown(name) << "\n";
            }
            return 0;
        }
        if (option == "--update" && argc == 3)
            return update(argv[2]);
    } catch (const armour::InputError &e) {
        std::cerr << "scene_keys: error: " << e.what() << '\n';
        return 2;
    }
    std::cerr << "usage: scene_keys --markdown | --update docs/scenes.md\n";
    return 1;
}
