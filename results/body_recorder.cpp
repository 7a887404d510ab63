#include "body_recorder.h"

#include "hdf5_handles.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace armour {
namespace {

namespace fs = std::filesystem;
using hdf5::Handle;
using hdf5::QuietErrors;

herr_t keep_innermost(unsigned, const H5E_error2_t *error, void *client) {
    if (error->desc != nullptr && error->desc[0] != '\0')
        *static_cast<std::string *>(client) = error->desc;
    return 0;
}

// The innermost entry names the actual cause (errno text, missing object);
// the outer ones only repeat "unable to create file".
std::string hdf5_reason() {
    std::string reason;
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, keep_innermost, &reason);
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    return reason.empty() ? std::string("HDF5 error") : reason;
}

std::string xml_escape(const std::string &text) {
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

std::string number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
}

// Row width of each per-body series, in doubles.
constexpr int kVec = 3;
constexpr int kQuat = 4;

struct SeriesSpec {
    const char *name;
    int width;
    const char *units;
    const char *description;
};

// Order matters: append() fills the rows in this order.
const SeriesSpec kBodySeries[] = {
    {"position", kVec, "m", "centre of mass position, world frame"},
    {"orientation", kQuat, "-", "unit quaternion w x y z rotating the unit frame to the world frame"},
    {"velocity", kVec, "m/s", "centre of mass velocity, world frame"},
    {"angular_velocity", kVec, "rad/s", "angular velocity, world frame"},
    {"external_force", kVec, "N", "external force as set, acting at the centre of mass, world frame"},
    {"external_torque", kVec, "N m", "external torque as set, about the centre of mass, world frame"},
    {"contact_force", kVec, "N", "total force from contacts with walls and other bodies, world frame"},
};
constexpr int kBodySeriesCount = static_cast<int>(sizeof kBodySeries / sizeof kBodySeries[0]);

} // namespace

struct BodyRecorder::Impl {
    std::string h5_path, xdmf_path, h5_reference; // h5_reference: as written in the XDMF
    Handle file;
    Handle time;
    std::vector<Handle> body_series; // as kBodySeries
    Handle points;
    std::vector<const TriangleMesh *> body_mesh;
    std::vector<RecorderUnit> units;
    long vertex_total = 0, triangle_total = 0;
    long step_count = 0;
    std::vector<double> times; // of the steps written
    std::vector<double> row;
    std::vector<float> point_row;
    bool compress = true;

    [[noreturn]] void fail(const std::string &what) const { throw InputError(h5_path + ": " + what); }
    hid_t check(hid_t id, const std::string &what) const {
        if (id < 0)
            fail(what + " (" + hdf5_reason() + ")");
        return id;
    }
    void check_status(herr_t status, const std::string &what) const {
        if (status < 0)
            fail(what + " (" + hdf5_reason() + ")");
    }

    Handle group(hid_t parent, const std::string &name) {
        return Handle(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                            "cannot create group " + name),
                      H5Gclose);
    }

    void string_attribute(hid_t object, const std::string &name, const std::string &value) {
        Handle type(check(H5Tcopy(H5T_C_S1), "cannot make a string type"), H5Tclose);
        check_status(H5Tset_size(type.get(), value.size() + 1), "cannot size a string type");
        check_status(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "cannot set string padding");
        check_status(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot set string encoding");
        Handle space(check(H5Screate(H5S_SCALAR), "cannot make a scalar space"), H5Sclose);
        Handle attribute(
            check(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                  "cannot create attribute " + name),
            H5Aclose);
        check_status(H5Awrite(attribute.get(), type.get(), value.c_str()), "cannot write attribute " + name);
    }

    void describe(hid_t dataset, const std::string &units_text, const std::string &description) {
        string_attribute(dataset, "units", units_text);
        string_attribute(dataset, "description", description);
    }

    // A dataset written once, whole.
    void fixed(hid_t parent, const std::string &name, const std::vector<hsize_t> &dims, hid_t file_type,
               hid_t memory_type, const void *data, const std::string &units_text,
               const std::string &description) {
        Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                           "cannot make the space of " + name),
                     H5Sclose);
        Handle dataset(check(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                        H5P_DEFAULT, H5P_DEFAULT),
                             "cannot create dataset " + name),
                       H5Dclose);
        if (H5Sget_simple_extent_npoints(space.get()) > 0)
            check_status(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                         "cannot write dataset " + name);
        describe(dataset.get(), units_text, description);
    }

    // A (steps, inner...) dataset that grows by one step per append.
    Handle series(hid_t parent, const std::string &name, const std::vector<hsize_t> &inner, hid_t file_type,
                  const std::string &units_text, const std::string &description) {
        std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{1};
        std::size_t row_bytes = H5Tget_size(file_type);
        for (hsize_t d : inner) {
            dims.push_back(d);
            // A zero extent cannot hold a chunk of 1; unlimited lets an empty scene still be written.
            max_dims.push_back(d == 0 ? H5S_UNLIMITED : d);
            chunk.push_back(std::max<hsize_t>(d, 1));
            row_bytes *= std::max<hsize_t>(d, 1);
        }
        // About 64 KiB per chunk: small scenes would otherwise store one tiny
        // compressed chunk per step, with per-chunk overhead larger than the data.
        chunk[0] = std::clamp<hsize_t>(65536 / std::max<std::size_t>(row_bytes, 1), 1, 1024);
        Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims.data()),
                           "cannot make the space of " + name),
                     H5Sclose);
        Handle create(check(H5Pcreate(H5P_DATASET_CREATE), "cannot make a property list"), H5Pclose);
        check_status(H5Pset_chunk(create.get(), static_cast<int>(chunk.size()), chunk.data()),
                     "cannot chunk " + name);
        if (compress) {
            check_status(H5Pset_shuffle(create.get()), "cannot shuffle " + name);
            check_status(H5Pset_deflate(create.get(), 4), "cannot compress " + name);
        }
        Handle dataset(check(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                        create.get(), H5P_DEFAULT),
                             "cannot create dataset " + name),
                       H5Dclose);
        describe(dataset.get(), units_text, description);
        return dataset;
    }

    void append_row(const Handle &dataset, hid_t memory_type, const void *data, const std::string &name) {
        Handle old_space(check(H5Dget_space(dataset.get()), "cannot read the space of " + name), H5Sclose);
        const int rank = H5Sget_simple_extent_ndims(old_space.get());
        std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)));
        H5Sget_simple_extent_dims(old_space.get(), dims.data(), nullptr);
        dims[0] = static_cast<hsize_t>(step_count) + 1;
        check_status(H5Dset_extent(dataset.get(), dims.data()), "cannot extend " + name);
        Handle space(check(H5Dget_space(dataset.get()), "cannot read the space of " + name), H5Sclose);
        std::vector<hsize_t> start(dims.size(), 0), count(dims);
        start[0] = static_cast<hsize_t>(step_count);
        count[0] = 1;
        hsize_t elements = 1;
        for (hsize_t c : count)
            elements *= c;
        if (elements == 0)
            return;
        check_status(
            H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
            "cannot select a step of " + name);
        Handle memory(check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                            "cannot make a memory space"),
                      H5Sclose);
        check_status(H5Dwrite(dataset.get(), memory_type, memory.get(), space.get(), H5P_DEFAULT, data),
                     "cannot write a step of " + name);
    }

    // What creating and reopening share: the paths, and each body's mesh.
    void prepare(const std::string &h5, const std::string &xdmf, const std::vector<RecorderUnit> &unit_list,
                 const std::vector<int> &body_unit) {
        h5_path = h5;
        xdmf_path = xdmf;
        units = unit_list;
        for (std::size_t k = 0; k < units.size(); ++k) {
            const TriangleMesh &mesh = units[k].mesh;
            for (const auto &triangle : mesh.triangles)
                for (int index : triangle)
                    if (index < 0 || index >= static_cast<int>(mesh.vertices.size()))
                        fail("unit " + std::to_string(k) + " (" + units[k].name + ") has a triangle index " +
                             std::to_string(index) + " outside its " + std::to_string(mesh.vertices.size()) +
                             " vertices");
        }
        for (std::size_t i = 0; i < body_unit.size(); ++i) {
            if (body_unit[i] < 0 || body_unit[i] >= static_cast<int>(units.size()))
                fail("body " + std::to_string(i) + " refers to unit " + std::to_string(body_unit[i]) +
                     " but there are " + std::to_string(units.size()) + " units");
            const TriangleMesh &mesh = units[static_cast<std::size_t>(body_unit[i])].mesh;
            body_mesh.push_back(&mesh);
            vertex_total += static_cast<long>(mesh.vertices.size());
            triangle_total += static_cast<long>(mesh.triangles.size());
        }
        // The XDMF names the HDF5 file relative to itself when they share a
        // folder, so the pair can be moved or copied together.
        const fs::path h5_abs = fs::absolute(h5_path).lexically_normal();
        const fs::path xdmf_abs = fs::absolute(xdmf_path).lexically_normal();
        h5_reference =
            h5_abs.parent_path() == xdmf_abs.parent_path() ? h5_abs.filename().string() : h5_abs.string();
        if (h5_reference.find_first_of(":|") != std::string::npos)
            fail("the XDMF index cannot name an HDF5 file whose path contains ':' or '|' (its separators)");
    }

    // Cuts an appendable series back to `steps` rows.
    void truncate(const Handle &dataset, long steps, const std::string &name) {
        Handle space(check(H5Dget_space(dataset.get()), "cannot read the space of " + name), H5Sclose);
        const int rank = H5Sget_simple_extent_ndims(space.get());
        std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)));
        H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
        if (dims[0] < static_cast<hsize_t>(steps))
            fail(name + " holds " + std::to_string(dims[0]) + " steps, fewer than the " +
                 std::to_string(steps) + " the checkpoint recorded");
        dims[0] = static_cast<hsize_t>(steps);
        check_status(H5Dset_extent(dataset.get(), dims.data()), "cannot truncate " + name);
    }

    std::string hdf(const std::string &dataset) const { return xml_escape(h5_reference) + ":" + dataset; }

    std::string grid(long step, double time_value, std::size_t total_steps) const {
        const std::string v = std::to_string(vertex_total), t = std::to_string(triangle_total);
        std::ostringstream out;
        out << "      <Grid Name=\"step_" << step << "\" GridType=\"Uniform\">\n"
            << "        <Time Value=\"" << number(time_value) << "\"/>\n"
            << "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << t << "\">\n"
            << "          <DataItem Dimensions=\"" << t
            << " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << hdf("/shapes/triangles")
            << "</DataItem>\n"
            << "        </Topology>\n"
            << "        <Geometry GeometryType=\"XYZ\">\n"
            // Xdmf3's own hyperslab form, "file:/dataset|start:stride:count:extent".
            // ParaView's Xdmf3 readers return no points for the XDMF 2
            // ItemType="HyperSlab" wrapper.
            << "          <DataItem Dimensions=\"" << v
            << " 3\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">" << hdf("/shapes/points") << "|"
            << step << " 0 0:1 1 1:1 " << v << " 3:" << total_steps << " " << v << " 3</DataItem>\n"
            << "        </Geometry>\n";
        for (const char *field : {"body", "unit"})
            out << "        <Attribute Name=\"" << field << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
                << "          <DataItem Dimensions=\"" << t
                << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                << hdf(std::string("/shapes/triangle_") + field) << "</DataItem>\n"
                << "        </Attribute>\n";
        out << "      </Grid>\n";
        return out.str();
    }

    // All grids again: each hyperslab names the dataset's current extent,
    // which grows with every step.
    void write_xdmf(const std::vector<double> &step_times) const {
        std::string text = "<?xml version=\"1.0\" ?>\n"
                           "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                           "<Xdmf Version=\"3.0\">\n"
                           "  <Domain>\n"
                           "    <Grid Name=\"bodies\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
        for (std::size_t step = 0; step < step_times.size(); ++step)
            text += grid(static_cast<long>(step), step_times[step], step_times.size());
        text += "    </Grid>\n  </Domain>\n</Xdmf>\n";

        // Readers must never see a half-written index: write beside it, then rename.
        const std::string temporary = xdmf_path + ".tmp";
        {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            if (!out)
                throw InputError(xdmf_path + ": cannot write " + temporary);
            out << text;
            out.flush();
            if (!out)
                throw InputError(xdmf_path + ": cannot write " + temporary);
        }
        std::error_code error;
        fs::rename(temporary, xdmf_path, error);
        if (error)
            throw InputError(xdmf_path + ": cannot replace the file (" + error.message() + ")");
    }
};

BodyRecorder::BodyRecorder(const std::string &h5_path, const std::string &xdmf_path,
                           const std::vector<RecorderUnit> &units, const std::vector<int> &body_unit,
                           const std::vector<std::pair<std::string, std::string>> &attributes, bool compress)
    : impl_(std::make_unique<Impl>()) {
    Impl &r = *impl_;
    r.compress = compress;
    r.prepare(h5_path, xdmf_path, units, body_unit);

    QuietErrors quiet;
    r.file = Handle(
        r.check(H5Fcreate(h5_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "cannot create file"),
        H5Fclose);
    const hid_t root = r.file.get();
    r.string_attribute(root, "units_system", "SI");
    r.string_attribute(root, "layout", "armour-fsi rigid-body results 1");
    for (const auto &[key, value] : attributes)
        r.string_attribute(root, key, value);

    r.time = r.series(root, "time", {}, H5T_IEEE_F64LE, "s", "simulated time of each output step");

    const hsize_t n = body_unit.size();
    Handle bodies = r.group(root, "bodies");
    std::vector<int> ids(n);
    for (std::size_t i = 0; i < n; ++i)
        ids[i] = static_cast<int>(i);
    r.fixed(bodies.get(), "id", {n}, H5T_STD_I32LE, H5T_NATIVE_INT, ids.data(), "-",
            "body index, as in the rigid-body engine");
    r.fixed(bodies.get(), "unit", {n}, H5T_STD_I32LE, H5T_NATIVE_INT, body_unit.data(), "-",
            "index k of the body's unit shape, /units/<k>");
    for (const SeriesSpec &spec : kBodySeries)
        r.body_series.push_back(r.series(bodies.get(), spec.name, {n, static_cast<hsize_t>(spec.width)},
                                         H5T_IEEE_F64LE, spec.units, spec.description));

    Handle unit_group = r.group(root, "units");
    for (std::size_t k = 0; k < units.size(); ++k) {
        Handle unit = r.group(unit_group.get(), std::to_string(k));
        r.string_attribute(unit.get(), "name", units[k].name);
        const TriangleMesh &mesh = units[k].mesh;
        std::vector<double> vertices;
        for (const Eigen::Vector3d &p : mesh.vertices)
            vertices.insert(vertices.end(), {p.x(), p.y(), p.z()});
        std::vector<int> triangles;
        for (const auto &triangle : mesh.triangles)
            triangles.insert(triangles.end(), triangle.begin(), triangle.end());
        r.fixed(unit.get(), "vertices", {mesh.vertices.size(), 3}, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                vertices.data(), "m", "exact unit shape, unit frame (origin at the centre of mass)");
        r.fixed(unit.get(), "triangles", {mesh.triangles.size(), 3}, H5T_STD_I32LE, H5T_NATIVE_INT,
                triangles.data(), "-", "vertex indices, counter-clockwise seen from outside");
    }

    Handle shapes = r.group(root, "shapes");
    std::vector<int> triangles, triangle_body, triangle_unit;
    int offset = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (const auto &triangle : r.body_mesh[i]->triangles) {
            for (int index : triangle)
                triangles.push_back(offset + index);
            triangle_body.push_back(static_cast<int>(i));
            triangle_unit.push_back(body_unit[i]);
        }
        offset += static_cast<int>(r.body_mesh[i]->vertices.size());
    }
    const auto v = static_cast<hsize_t>(r.vertex_total), t = static_cast<hsize_t>(r.triangle_total);
    r.points = r.series(shapes.get(), "points", {v, 3}, H5T_IEEE_F32LE, "m",
                        "every body's unit mesh moved to its pose, bodies in order, world frame");
    r.fixed(shapes.get(), "triangles", {t, 3}, H5T_STD_I32LE, H5T_NATIVE_INT, triangles.data(), "-",
            "vertex indices into the second axis of /shapes/points");
    r.fixed(shapes.get(), "triangle_body", {t}, H5T_STD_I32LE, H5T_NATIVE_INT, triangle_body.data(), "-",
            "body index of each triangle of /shapes/triangles");
    r.fixed(shapes.get(), "triangle_unit", {t}, H5T_STD_I32LE, H5T_NATIVE_INT, triangle_unit.data(), "-",
            "unit index of each triangle of /shapes/triangles");

    r.check_status(H5Fflush(root, H5F_SCOPE_GLOBAL), "cannot flush");
    r.write_xdmf({});
}

std::unique_ptr<BodyRecorder> BodyRecorder::reopen(const std::string &h5_path, const std::string &xdmf_path,
                                                   const std::vector<RecorderUnit> &units,
                                                   const std::vector<int> &body_unit, long keep_steps) {
    std::unique_ptr<BodyRecorder> recorder(new BodyRecorder());
    recorder->impl_ = std::make_unique<Impl>();
    Impl &r = *recorder->impl_;
    r.prepare(h5_path, xdmf_path, units, body_unit);
    QuietErrors quiet;
    r.file = Handle(r.check(H5Fopen(h5_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "cannot reopen the file"),
                    H5Fclose);
    const hid_t root = r.file.get();
    const auto open = [&](const std::string &name) {
        return Handle(r.check(H5Dopen2(root, name.c_str(), H5P_DEFAULT), "cannot open " + name), H5Dclose);
    };
    r.time = open("time");
    for (const SeriesSpec &spec : kBodySeries)
        r.body_series.push_back(open(std::string("bodies/") + spec.name));
    r.points = open("shapes/points");
    {
        Handle space(r.check(H5Dget_space(r.body_series[0].get()), "cannot read bodies/position"), H5Sclose);
        hsize_t dims[3] = {0, 0, 0};
        H5Sget_simple_extent_dims(space.get(), dims, nullptr);
        if (dims[1] != body_unit.size())
            r.fail("holds " + std::to_string(dims[1]) + " bodies, the scene " +
                   std::to_string(body_unit.size()));
    }
    r.truncate(r.time, keep_steps, "time");
    for (std::size_t s = 0; s < r.body_series.size(); ++s)
        r.truncate(r.body_series[s], keep_steps, std::string("bodies/") + kBodySeries[s].name);
    r.truncate(r.points, keep_steps, "shapes/points");
    r.times.assign(static_cast<std::size_t>(keep_steps), 0.0);
    if (keep_steps > 0)
        r.check_status(
            H5Dread(r.time.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.times.data()),
            "cannot read time");
    r.step_count = keep_steps;
    r.check_status(H5Fflush(root, H5F_SCOPE_GLOBAL), "cannot flush");
    r.write_xdmf(r.times);
    return recorder;
}

BodyRecorder::~BodyRecorder() {
    try {
        close();
    } catch (...) {
        // A destructor may run during unwinding; the first error is the one to report.
    }
}

void BodyRecorder::append(double time, const std::vector<BodyState> &states) {
    Impl &r = *impl_;
    if (r.file.get() < 0)
        r.fail("append after close");
    if (states.size() != r.body_mesh.size())
        r.fail("append got " + std::to_string(states.size()) + " body states for " +
               std::to_string(r.body_mesh.size()) + " bodies");

    QuietErrors quiet;
    r.append_row(r.time, H5T_NATIVE_DOUBLE, &time, "time");
    for (int s = 0; s < kBodySeriesCount; ++s) {
        r.row.clear();
        for (const BodyState &state : states) {
            const Eigen::Quaterniond &q = state.pose.orientation;
            switch (s) {
            case 0:
                r.row.insert(r.row.end(), state.pose.position.data(), state.pose.position.data() + 3);
                break;
            case 1:
                r.row.insert(r.row.end(), {q.w(), q.x(), q.y(), q.z()});
                break;
            case 2:
                r.row.insert(r.row.end(), state.velocity.data(), state.velocity.data() + 3);
                break;
            case 3:
                r.row.insert(r.row.end(), state.angular_velocity.data(), state.angular_velocity.data() + 3);
                break;
            case 4:
                r.row.insert(r.row.end(), state.external_force.data(), state.external_force.data() + 3);
                break;
            case 5:
                r.row.insert(r.row.end(), state.external_torque.data(), state.external_torque.data() + 3);
                break;
            default:
                r.row.insert(r.row.end(), state.contact_force.data(), state.contact_force.data() + 3);
                break;
            }
        }
        r.append_row(r.body_series[static_cast<std::size_t>(s)], H5T_NATIVE_DOUBLE, r.row.data(),
                     std::string("bodies/") + kBodySeries[s].name);
    }

    r.point_row.clear();
    for (std::size_t i = 0; i < states.size(); ++i) {
        // Engines integrate quaternions and let the norm drift; a drifted
        // quaternion would scale the drawn shape.
        const Eigen::Matrix3d rotation = states[i].pose.orientation.normalized().toRotationMatrix();
        for (const Eigen::Vector3d &p : r.body_mesh[i]->vertices) {
            const Eigen::Vector3d world = states[i].pose.position + rotation * p;
            r.point_row.insert(r.point_row.end(),
                               {static_cast<float>(world.x()), static_cast<float>(world.y()),
                                static_cast<float>(world.z())});
        }
    }
    r.append_row(r.points, H5T_NATIVE_FLOAT, r.point_row.data(), "shapes/points");

    // Flush before the XDMF names the step, so the index never points past
    // what is on disk.
    r.check_status(H5Fflush(r.file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
    r.times.push_back(time);
    try {
        r.write_xdmf(r.times);
    } catch (...) {
        r.times.pop_back();
        throw;
    }
    ++r.step_count;
}

void BodyRecorder::close() {
    Impl &r = *impl_;
    if (r.file.get() < 0)
        return;
    QuietErrors quiet;
    r.time.reset();
    for (Handle &dataset : r.body_series)
        dataset.reset();
    r.points.reset();
    const herr_t status = r.file.reset();
    r.check_status(status, "cannot close");
}

long BodyRecorder::steps() const {
    return impl_->step_count;
}

} // namespace armour
