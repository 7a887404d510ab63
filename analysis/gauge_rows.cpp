#include "gauge_rows.h"

#include "checkpoints.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace armour {

namespace fs = std::filesystem;

std::vector<std::vector<double>> gauge_rows(const fs::path &case_dir) {
    // The start-time folders, in time order (their names are numbers).
    std::vector<std::pair<double, fs::path>> parts;
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(case_dir / "postProcessing" / "gauges", ec)) {
        const std::string name = e.path().filename().string();
        const std::optional<double> start = time_of_name(name);
        if (e.is_directory() && start && fs::is_regular_file(e.path() / "surfaceElevation.dat"))
            parts.emplace_back(*start, e.path() / "surfaceElevation.dat");
    }
    std::sort(parts.begin(), parts.end());
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        // The next part starts at a checkpoint's time and computes the steps after it again.
        const double until = k + 1 < parts.size() ? parts[k + 1].first : HUGE_VAL;
        std::ifstream in(parts[k].second);
        for (std::string line; std::getline(in, line);) {
            // A line without its newline is one the solver is still writing.
            if (line.empty() || line[0] == '#' || in.eof())
                continue;
            std::istringstream s(line);
            std::vector<double> row;
            for (double v; s >> v;)
                row.push_back(v);
            if (row.empty() || row[0] > until * (1.0 + 1e-12))
                continue;
            if (!rows.empty() && row[0] <= rows.back()[0])
                continue; // not after the last row kept
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

} // namespace armour
