// BodyRecorder: the HDF5 layout read back with the plain C API, the XDMF
// index checked against it, crash safety and error reporting.
#include "body_recorder.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using armour::BodyRecorder;
using armour::BodyState;
using armour::InputError;
using armour::RecorderUnit;
using armour::TriangleMesh;

namespace {

TriangleMesh tetrahedron() {
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
    return m;
}

TriangleMesh cube(double half) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back((i & 1) ? half : -half, (i & 2) ? half : -half, (i & 4) ? half : -half);
    m.triangles = {{{0, 2, 1}}, {{1, 2, 3}}, {{4, 5, 6}}, {{5, 7, 6}}, {{0, 1, 4}}, {{1, 5, 4}},
                   {{2, 6, 3}}, {{3, 6, 7}}, {{0, 4, 2}}, {{2, 4, 6}}, {{1, 3, 5}}, {{3, 7, 5}}};
    return m;
}

const std::vector<RecorderUnit> kUnits = {{"tetra", tetrahedron()}, {"cube", cube(0.5)}};
const std::vector<int> kBodyUnit = {0, 1, 0};
constexpr int kSteps = 5;

double time_of(int step) {
    return 0.25 * step + 0.1;
}

// Distinct values per step, body and field, so a transposed or shifted
// write cannot pass.
BodyState state_of(int step, int body) {
    BodyState s;
    const double t = time_of(step);
    s.pose.position = Eigen::Vector3d(body + t, -2.0 * body + 0.5 * t, 3.0 + t * t);
    s.pose.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.7 * t + body, Eigen::Vector3d(1, 2, 3).normalized()));
    s.velocity = Eigen::Vector3d(10 + body, 20 + step, 30);
    s.angular_velocity = Eigen::Vector3d(-1.0 * body, 0.5 * step, 0.25);
    s.external_force = Eigen::Vector3d(100.0 * body, 7, -step);
    s.external_torque = Eigen::Vector3d(1, 2, 3) * (step + 1);
    s.contact_force = Eigen::Vector3d(0, 0, 9.81 * (body + 1) * step);
    return s;
}

std::vector<BodyState> states_of(int step) {
    std::vector<BodyState> states;
    for (int body = 0; body < static_cast<int>(kBodyUnit.size()); ++body)
        states.push_back(state_of(step, body));
    return states;
}

// A fresh folder per test, removed afterwards.
class ResultsTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               (std::string("armour_results_") + info->name() + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string &name) const { return (dir_ / name).string(); }

    void write_run(const std::string &h5, const std::string &xdmf, int steps) {
        BodyRecorder recorder(h5, xdmf, kUnits, kBodyUnit, {{"scene", "two units"}, {"dt", "1e-4"}});
        for (int step = 0; step < steps; ++step)
            recorder.append(time_of(step), states_of(step));
        EXPECT_EQ(recorder.steps(), steps);
        recorder.close();
    }

    fs::path dir_;
};

// Minimal RAII for the reading side.
struct Id {
    hid_t id;
    herr_t (*closer)(hid_t);
    ~Id() {
        if (id >= 0)
            closer(id);
    }
};

std::vector<hsize_t> dims_of(hid_t file, const std::string &name) {
    Id dataset{H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose};
    if (dataset.id < 0)
        return {};
    Id space{H5Dget_space(dataset.id), H5Sclose};
    std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.id)));
    H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
    return dims;
}

template <class T> std::vector<T> read_all(hid_t file, const std::string &name, hid_t memory_type) {
    Id dataset{H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose};
    Id space{H5Dget_space(dataset.id), H5Sclose};
    std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id)));
    if (!values.empty()) {
        EXPECT_GE(H5Dread(dataset.id, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0) << name;
    }
    return values;
}

std::string string_attribute(hid_t object, const std::string &name) {
    if (H5Aexists(object, name.c_str()) <= 0)
        return "<missing>";
    Id attribute{H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose};
    Id type{H5Aget_type(attribute.id), H5Tclose};
    if (H5Tget_class(type.id) != H5T_STRING || H5Tis_variable_str(type.id) > 0)
        return "<not a fixed string>";
    std::string value(H5Tget_size(type.id), '\0');
    H5Aread(attribute.id, type.id, value.data());
    return value.substr(0, value.find('\0'));
}

std::string dataset_attribute(hid_t file, const std::string &dataset_name, const std::string &name) {
    Id dataset{H5Dopen2(file, dataset_name.c_str(), H5P_DEFAULT), H5Dclose};
    return dataset.id < 0 ? "<no dataset>" : string_attribute(dataset.id, name);
}

std::string read_text(const std::string &path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every start tag is closed in order; enough to catch a truncated or spliced file.
bool tags_balanced(const std::string &xml, std::string *problem) {
    std::vector<std::string> open;
    const std::regex tag(R"(<(/?)([A-Za-z_][\w:.-]*)[^<>]*?(/?)>)");
    std::string stripped = std::regex_replace(xml, std::regex(R"(<\?[^>]*\?>|<!DOCTYPE[^>]*>)"), "");
    for (auto it = std::sregex_iterator(stripped.begin(), stripped.end(), tag); it != std::sregex_iterator();
         ++it) {
        const std::smatch &m = *it;
        if (m[3] == "/")
            continue;
        if (m[1] == "/") {
            if (open.empty() || open.back() != m[2]) {
                *problem = "unexpected </" + m[2].str() + ">";
                return false;
            }
            open.pop_back();
        } else {
            open.push_back(m[2]);
        }
    }
    if (!open.empty())
        *problem = "unclosed <" + open.back() + ">";
    return open.empty();
}

struct XdmfGrid {
    double time = 0.0;
    std::vector<long> geometry_dims; // Dimensions of the geometry's DataItem
    std::vector<long> slab;          // start, stride, count (9 numbers)
    std::vector<long> source_dims;   // the extent the hyperslab expects
    std::vector<std::string> paths;  // every "file:/dataset" reference
};

std::vector<long> numbers(const std::string &text) {
    std::vector<long> out;
    std::istringstream in(text);
    long value;
    while (in >> value)
        out.push_back(value);
    return out;
}

std::vector<std::string> split(const std::string &text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator))
        parts.push_back(part);
    return parts;
}

std::vector<XdmfGrid> parse_grids(const std::string &xml) {
    std::vector<XdmfGrid> grids;
    const std::regex grid_re(R"(<Grid Name="step_\d+"[\s\S]*?</Grid>)");
    const std::regex time_re(R"re(<Time Value="([^"]+)")re");
    const std::regex geometry_re(
        R"re(<Geometry GeometryType="XYZ">\s*<DataItem Dimensions="([^"]+)"[^>]*>([^<]+)<)re");
    const std::regex hdf_re(R"re(Format="HDF">([^<]+)</DataItem>)re");
    for (auto it = std::sregex_iterator(xml.begin(), xml.end(), grid_re); it != std::sregex_iterator();
         ++it) {
        const std::string text = it->str();
        XdmfGrid grid;
        std::smatch m;
        if (std::regex_search(text, m, time_re))
            grid.time = std::stod(m[1]);
        if (std::regex_search(text, m, geometry_re)) {
            grid.geometry_dims = numbers(m[1]);
            // "file:/dataset|start:stride:count:extent"
            const std::vector<std::string> parts = split(m[2], '|');
            if (parts.size() == 2) {
                const std::vector<std::string> rows = split(parts[1], ':');
                for (std::size_t r = 0; r < 3 && r < rows.size(); ++r)
                    for (long value : numbers(rows[r]))
                        grid.slab.push_back(value);
                if (rows.size() == 4)
                    grid.source_dims = numbers(rows[3]);
            }
        }
        for (auto h = std::sregex_iterator(text.begin(), text.end(), hdf_re); h != std::sregex_iterator();
             ++h)
            grid.paths.push_back(split((*h)[1], '|').front());
        grids.push_back(grid);
    }
    return grids;
}

// Checks the XDMF against the HDF5 file it names: one grid per step, each
// reading step s of /shapes/points and datasets that exist.
void expect_xdmf_matches(const std::string &xdmf_path, const std::string &h5_path, int steps) {
    const std::string xml = read_text(xdmf_path);
    std::string problem;
    EXPECT_TRUE(tags_balanced(xml, &problem)) << problem;
    EXPECT_NE(xml.find("<Xdmf Version=\"3.0\""), std::string::npos);
    EXPECT_NE(xml.find("CollectionType=\"Temporal\""), std::string::npos);

    Id file{H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(file.id, 0);
    const std::vector<hsize_t> points = dims_of(file.id, "/shapes/points");
    ASSERT_EQ(points.size(), 3u);
    ASSERT_EQ(points[0], static_cast<hsize_t>(steps));
    const auto v = static_cast<long>(points[1]);

    const std::vector<XdmfGrid> grids = parse_grids(xml);
    ASSERT_EQ(grids.size(), static_cast<std::size_t>(steps));
    const std::string h5_name = fs::path(h5_path).filename().string();
    for (int s = 0; s < steps; ++s) {
        SCOPED_TRACE("step " + std::to_string(s));
        EXPECT_DOUBLE_EQ(grids[s].time, time_of(s));
        EXPECT_EQ(grids[s].geometry_dims, (std::vector<long>{v, 3}));
        EXPECT_EQ(grids[s].slab, (std::vector<long>{s, 0, 0, 1, 1, 1, 1, v, 3}));
        EXPECT_EQ(grids[s].source_dims, (std::vector<long>{steps, v, 3}));
        ASSERT_EQ(grids[s].paths.size(), 4u);
        for (const std::string &reference : grids[s].paths) {
            const std::size_t colon = reference.find(':');
            ASSERT_NE(colon, std::string::npos) << reference;
            EXPECT_EQ(reference.substr(0, colon), h5_name);
            const std::string dataset = reference.substr(colon + 1);
            EXPECT_FALSE(dims_of(file.id, dataset).empty()) << dataset << " is not in the file";
        }
    }
}

} // namespace

TEST_F(ResultsTest, DatasetsHaveTheDocumentedShapesValuesAndUnits) {
    const std::string h5 = path("run.h5");
    write_run(h5, path("run.xdmf"), kSteps);

    Id file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(file.id, 0);
    const hsize_t n = kBodyUnit.size(), v = 4 + 8 + 4, t = 4 + 12 + 4, s = kSteps;

    const std::map<std::string, std::pair<std::vector<hsize_t>, std::string>> expected = {
        {"/time", {{s}, "s"}},
        {"/bodies/id", {{n}, "-"}},
        {"/bodies/unit", {{n}, "-"}},
        {"/bodies/position", {{s, n, 3}, "m"}},
        {"/bodies/orientation", {{s, n, 4}, "-"}},
        {"/bodies/velocity", {{s, n, 3}, "m/s"}},
        {"/bodies/angular_velocity", {{s, n, 3}, "rad/s"}},
        {"/bodies/external_force", {{s, n, 3}, "N"}},
        {"/bodies/external_torque", {{s, n, 3}, "N m"}},
        {"/bodies/contact_force", {{s, n, 3}, "N"}},
        {"/units/0/vertices", {{4, 3}, "m"}},
        {"/units/0/triangles", {{4, 3}, "-"}},
        {"/units/1/vertices", {{8, 3}, "m"}},
        {"/units/1/triangles", {{12, 3}, "-"}},
        {"/shapes/points", {{s, v, 3}, "m"}},
        {"/shapes/triangles", {{t, 3}, "-"}},
        {"/shapes/triangle_body", {{t}, "-"}},
        {"/shapes/triangle_unit", {{t}, "-"}},
    };
    for (const auto &[name, shape_units] : expected) {
        SCOPED_TRACE(name);
        EXPECT_EQ(dims_of(file.id, name), shape_units.first);
        EXPECT_EQ(dataset_attribute(file.id, name, "units"), shape_units.second);
        EXPECT_GT(dataset_attribute(file.id, name, "description").size(), 10u);
    }
    EXPECT_EQ(string_attribute(file.id, "units_system"), "SI");
    EXPECT_EQ(string_attribute(file.id, "scene"), "two units");
    EXPECT_EQ(string_attribute(file.id, "dt"), "1e-4");
    {
        Id unit{H5Gopen2(file.id, "/units/1", H5P_DEFAULT), H5Gclose};
        EXPECT_EQ(string_attribute(unit.id, "name"), "cube");
    }

    // Time series grow along steps, chunked and deflated.
    for (const char *name : {"/time", "/bodies/position", "/shapes/points"}) {
        SCOPED_TRACE(name);
        Id dataset{H5Dopen2(file.id, name, H5P_DEFAULT), H5Dclose};
        Id create{H5Dget_create_plist(dataset.id), H5Pclose};
        EXPECT_EQ(H5Pget_layout(create.id), H5D_CHUNKED);
        EXPECT_GE(H5Pget_filter_by_id2(create.id, H5Z_FILTER_DEFLATE, nullptr, nullptr, nullptr, 0, nullptr,
                                       nullptr),
                  0);
        Id space{H5Dget_space(dataset.id), H5Sclose};
        hsize_t max_dims[3];
        H5Sget_simple_extent_dims(space.id, nullptr, max_dims);
        EXPECT_EQ(max_dims[0], H5S_UNLIMITED);
    }
    {
        Id dataset{H5Dopen2(file.id, "/shapes/points", H5P_DEFAULT), H5Dclose};
        Id type{H5Dget_type(dataset.id), H5Tclose};
        EXPECT_EQ(H5Tget_class(type.id), H5T_FLOAT);
        EXPECT_EQ(H5Tget_size(type.id), 4u);
    }

    const auto time = read_all<double>(file.id, "/time", H5T_NATIVE_DOUBLE);
    const auto ids = read_all<int>(file.id, "/bodies/id", H5T_NATIVE_INT);
    const auto units = read_all<int>(file.id, "/bodies/unit", H5T_NATIVE_INT);
    EXPECT_EQ(ids, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(units, kBodyUnit);
    const auto position = read_all<double>(file.id, "/bodies/position", H5T_NATIVE_DOUBLE);
    const auto orientation = read_all<double>(file.id, "/bodies/orientation", H5T_NATIVE_DOUBLE);
    const auto velocity = read_all<double>(file.id, "/bodies/velocity", H5T_NATIVE_DOUBLE);
    const auto omega = read_all<double>(file.id, "/bodies/angular_velocity", H5T_NATIVE_DOUBLE);
    const auto force = read_all<double>(file.id, "/bodies/external_force", H5T_NATIVE_DOUBLE);
    const auto torque = read_all<double>(file.id, "/bodies/external_torque", H5T_NATIVE_DOUBLE);
    const auto contact = read_all<double>(file.id, "/bodies/contact_force", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(time.size(), s);
    for (int step = 0; step < kSteps; ++step) {
        EXPECT_EQ(time[step], time_of(step));
        for (int b = 0; b < static_cast<int>(n); ++b) {
            const BodyState e = state_of(step, b);
            const std::size_t r3 = (step * n + b) * 3, r4 = (step * n + b) * 4;
            for (int k = 0; k < 3; ++k) {
                EXPECT_EQ(position[r3 + k], e.pose.position[k]);
                EXPECT_EQ(velocity[r3 + k], e.velocity[k]);
                EXPECT_EQ(omega[r3 + k], e.angular_velocity[k]);
                EXPECT_EQ(force[r3 + k], e.external_force[k]);
                EXPECT_EQ(torque[r3 + k], e.external_torque[k]);
                EXPECT_EQ(contact[r3 + k], e.contact_force[k]);
            }
            const Eigen::Quaterniond &q = e.pose.orientation;
            EXPECT_EQ(orientation[r4 + 0], q.w());
            EXPECT_EQ(orientation[r4 + 1], q.x());
            EXPECT_EQ(orientation[r4 + 2], q.y());
            EXPECT_EQ(orientation[r4 + 3], q.z());
        }
    }

    const auto vertices1 = read_all<double>(file.id, "/units/1/vertices", H5T_NATIVE_DOUBLE);
    const auto triangles1 = read_all<int>(file.id, "/units/1/triangles", H5T_NATIVE_INT);
    for (std::size_t i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(vertices1[i * 3 + k], kUnits[1].mesh.vertices[i][k]);
    for (std::size_t i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(triangles1[i * 3 + k], kUnits[1].mesh.triangles[i][k]);
}

TEST_F(ResultsTest, ShapePointsAreEachUnitMeshMovedToItsPose) {
    const std::string h5 = path("run.h5");
    write_run(h5, path("run.xdmf"), kSteps);
    Id file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(file.id, 0);
    const auto points = read_all<float>(file.id, "/shapes/points", H5T_NATIVE_FLOAT);
    const auto triangles = read_all<int>(file.id, "/shapes/triangles", H5T_NATIVE_INT);
    const auto triangle_body = read_all<int>(file.id, "/shapes/triangle_body", H5T_NATIVE_INT);
    const std::size_t v = 16;
    ASSERT_EQ(points.size(), kSteps * v * 3);

    for (int step = 0; step < kSteps; ++step) {
        std::size_t vertex = 0;
        for (int b = 0; b < 3; ++b) {
            const BodyState e = state_of(step, b);
            for (const Eigen::Vector3d &p : kUnits[kBodyUnit[b]].mesh.vertices) {
                const Eigen::Vector3d world = e.pose.position + e.pose.orientation * p;
                const std::size_t at = (step * v + vertex) * 3;
                const Eigen::Vector3d got(points[at], points[at + 1], points[at + 2]);
                // float32 keeps 24 bits: a relative error of 6e-8 on coordinates of order 10.
                EXPECT_LT((got - world).norm(), 1e-6 * (1.0 + world.norm()))
                    << "step " << step << " body " << b;
                ++vertex;
            }
        }
    }

    // Connectivity: body b's triangles are its unit's, shifted by the vertices before it.
    std::size_t triangle = 0;
    int offset = 0;
    for (int b = 0; b < 3; ++b) {
        const TriangleMesh &mesh = kUnits[kBodyUnit[b]].mesh;
        for (const auto &tri : mesh.triangles) {
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(triangles[triangle * 3 + k], tri[k] + offset);
            EXPECT_EQ(triangle_body[triangle], b);
            ++triangle;
        }
        offset += static_cast<int>(mesh.vertices.size());
    }
    EXPECT_EQ(triangle, triangles.size() / 3);
}

TEST_F(ResultsTest, XdmfIndexesEveryStepOfTheHdf5File) {
    const std::string h5 = path("run.h5"), xdmf = path("run.xdmf");
    write_run(h5, xdmf, kSteps);
    expect_xdmf_matches(xdmf, h5, kSteps);
    EXPECT_FALSE(fs::exists(xdmf + ".tmp"));
}

TEST_F(ResultsTest, EmptyRunStillHasAValidIndex) {
    const std::string h5 = path("run.h5"), xdmf = path("run.xdmf");
    write_run(h5, xdmf, 0);
    expect_xdmf_matches(xdmf, h5, 0);
}

// A killed run leaves the files as they are on disk at that moment. Copying
// them mid-run reproduces that state exactly; opening the live file again in
// this process would not, because HDF5 shares the already open file (and its
// caches) between handles of one process. The copy is also free of the
// writer's file lock, so no HDF5_USE_FILE_LOCKING setting is needed.
TEST_F(ResultsTest, FilesAreReadableAfterEachAppendWithoutClose) {
    const std::string h5 = path("run.h5"), xdmf = path("run.xdmf");
    BodyRecorder recorder(h5, xdmf, kUnits, kBodyUnit, {});
    for (int step = 0; step < 3; ++step) {
        recorder.append(time_of(step), states_of(step));
        SCOPED_TRACE("killed after step " + std::to_string(step));
        const std::string h5_copy = path("killed.h5"), xdmf_copy = path("killed.xdmf");
        fs::copy_file(h5, h5_copy, fs::copy_options::overwrite_existing);
        // The index names the HDF5 file by its own name; keep it pointing at the copy.
        std::string index = read_text(xdmf);
        index = std::regex_replace(index, std::regex("run\\.h5:"), "killed.h5:");
        std::ofstream(xdmf_copy) << index;

        expect_xdmf_matches(xdmf_copy, h5_copy, step + 1);
        Id file{H5Fopen(h5_copy.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
        ASSERT_GE(file.id, 0);
        const auto time = read_all<double>(file.id, "/time", H5T_NATIVE_DOUBLE);
        ASSERT_EQ(time.size(), static_cast<std::size_t>(step + 1));
        EXPECT_EQ(time.back(), time_of(step));
        const auto position = read_all<double>(file.id, "/bodies/position", H5T_NATIVE_DOUBLE);
        ASSERT_EQ(position.size(), (step + 1) * 3u * 3u);
        EXPECT_EQ(position[(step * 3 + 2) * 3], state_of(step, 2).pose.position.x());
    }
    EXPECT_EQ(recorder.steps(), 3);
    recorder.close();
    recorder.close();
    EXPECT_EQ(recorder.steps(), 3);
    EXPECT_THROW(recorder.append(1.0, states_of(0)), InputError);
}

TEST_F(ResultsTest, UnwritablePathThrowsOneLineWithoutHdf5Noise) {
    const std::string missing = path("no_such_dir/run.h5");
    testing::internal::CaptureStderr();
    try {
        BodyRecorder recorder(missing, path("run.xdmf"), kUnits, kBodyUnit, {});
        FAIL() << "no exception";
    } catch (const InputError &error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(missing + ": ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");

    EXPECT_THROW(BodyRecorder(path("run.h5"), path("no_such_dir/run.xdmf"), kUnits, kBodyUnit, {}),
                 InputError);
}

TEST_F(ResultsTest, InconsistentInputThrows) {
    EXPECT_THROW(BodyRecorder(path("a.h5"), path("a.xdmf"), kUnits, {0, 2}, {}), InputError);
    std::vector<RecorderUnit> broken = kUnits;
    broken[0].mesh.triangles.push_back({{0, 1, 4}});
    EXPECT_THROW(BodyRecorder(path("b.h5"), path("b.xdmf"), broken, kBodyUnit, {}), InputError);
    // Root attributes may not shadow the ones the recorder owns.
    EXPECT_THROW(
        BodyRecorder(path("c.h5"), path("c.xdmf"), kUnits, kBodyUnit, {{"units_system", "imperial"}}),
        InputError);

    BodyRecorder recorder(path("d.h5"), path("d.xdmf"), kUnits, kBodyUnit, {});
    EXPECT_THROW(recorder.append(0.0, {BodyState{}}), InputError);
    EXPECT_EQ(recorder.steps(), 0);
}

// The real consumer: ParaView's Xdmf3 reader must see every step with the
// posed points. Skipped where ParaView is not installed (it is not a build
// dependency).
TEST_F(ResultsTest, ParaViewXdmf3ReaderLoadsEveryStep) {
    if (std::system("command -v pvpython > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "pvpython not found";
    const std::string h5 = path("run.h5"), xdmf = path("run.xdmf"), script = path("read.py"),
                      table = path("read.txt");
    write_run(h5, xdmf, kSteps);
    std::ofstream(script)
        << "import sys\n"
           "from paraview.simple import Xdmf3ReaderS\n"
           "from paraview import servermanager as sm\n"
           "r = Xdmf3ReaderS(FileName=[sys.argv[1]])\n"
           "r.UpdatePipelineInformation()\n"
           "with open(sys.argv[2], 'w') as out:\n"
           "    for t in r.TimestepValues:\n"
           "        r.UpdatePipeline(t)\n"
           "        g = sm.Fetch(r)\n"
           "        body = g.GetCellData().GetArray('body')\n"
           "        out.write('%r %d %d' % (t, g.GetNumberOfPoints(), g.GetNumberOfCells()))\n"
           "        for i in range(g.GetNumberOfPoints()):\n"
           "            out.write(' %.9g %.9g %.9g' % g.GetPoint(i))\n"
           "        for c in range(g.GetNumberOfCells()):\n"
           "            out.write(' %d' % body.GetValue(c))\n"
           "        out.write('\\n')\n";
    const std::string command = "timeout 300 pvpython --force-offscreen-rendering " + script + " " + xdmf +
                                " " + table + " > " + path("pvpython.log") + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << read_text(path("pvpython.log"));

    std::ifstream in(table);
    std::string line;
    int step = 0;
    for (; std::getline(in, line); ++step) {
        SCOPED_TRACE("step " + std::to_string(step));
        ASSERT_LT(step, kSteps);
        std::istringstream row(line);
        double t = 0.0;
        int point_count = 0, cell_count = 0;
        row >> t >> point_count >> cell_count;
        EXPECT_DOUBLE_EQ(t, time_of(step));
        ASSERT_EQ(point_count, 16);
        ASSERT_EQ(cell_count, 20);
        for (int b = 0; b < 3; ++b) {
            const BodyState e = state_of(step, b);
            for (const Eigen::Vector3d &p : kUnits[kBodyUnit[b]].mesh.vertices) {
                Eigen::Vector3d got;
                row >> got.x() >> got.y() >> got.z();
                const Eigen::Vector3d world = e.pose.position + e.pose.orientation * p;
                EXPECT_LT((got - world).norm(), 1e-6 * (1.0 + world.norm())) << "body " << b;
            }
        }
        std::vector<int> bodies(static_cast<std::size_t>(cell_count));
        for (int &b : bodies)
            row >> b;
        EXPECT_EQ(bodies, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2}));
    }
    EXPECT_EQ(step, kSteps);
}
