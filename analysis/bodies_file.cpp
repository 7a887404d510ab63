#include "bodies_file.h"

#include "input_error.h"

#include "hdf5_handles.h"

#include <hdf5.h>

#include <algorithm>
#include <functional>

namespace armour {
namespace {

using hdf5::Handle;
using hdf5::QuietErrors;

struct Reader {
    std::string path;
    hid_t file;

    [[noreturn]] void fail(const std::string &what) const { throw InputError(path + ": " + what); }

    // All values of a dataset in storage order, converted to T, and its extents.
    template <class T>
    std::vector<T> read(const std::string &name, hid_t memory_type, std::vector<hsize_t> &dims) const {
        if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
            fail("no dataset " + name);
        Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
        if (set.get() < 0)
            fail("cannot open dataset " + name);
        Handle space(H5Dget_space(set.get()), H5Sclose);
        const int rank = H5Sget_simple_extent_ndims(space.get());
        dims.assign(static_cast<std::size_t>(std::max(rank, 0)), 0);
        H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
        hsize_t count = 1;
        for (const hsize_t d : dims)
            count *= d;
        std::vector<T> data(count);
        if (count > 0 && H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
            fail("cannot read dataset " + name);
        return data;
    }

    // A (steps, bodies, width) dataset, each row made into an Eigen value by
    // `make`: at least `steps` rows, as many as it holds (a running solver
    // extends /time first, then each series).
    template <class T>
    BodiesFile::Series<T> series(const std::string &name, std::size_t steps, std::size_t bodies,
                                 std::size_t width, const std::function<T(const double *)> &make) const {
        std::vector<hsize_t> dims;
        const std::vector<double> data = read<double>(name, H5T_NATIVE_DOUBLE, dims);
        if (dims.size() != 3 || dims[0] + 1 < steps || dims[1] != bodies || dims[2] != width)
            fail(name + " is not (" + std::to_string(steps) + ", " + std::to_string(bodies) + ", " +
                 std::to_string(width) + ")");
        BodiesFile::Series<T> out(std::min<std::size_t>(steps, dims[0]));
        for (std::size_t s = 0; s < out.size(); ++s)
            for (std::size_t b = 0; b < bodies; ++b)
                out[s].push_back(make(&data[width * (s * bodies + b)]));
        return out;
    }
};

herr_t collect_string_attribute(hid_t object, const char *name, const H5A_info_t *, void *client) {
    Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    if (attribute.get() < 0 || type.get() < 0 || H5Tget_class(type.get()) != H5T_STRING ||
        H5Tis_variable_str(type.get()) > 0)
        return 0; // the recorder writes fixed-length strings only
    std::string value(H5Tget_size(type.get()), '\0');
    if (H5Aread(attribute.get(), type.get(), value.data()) >= 0)
        (*static_cast<std::map<std::string, std::string> *>(client))[name] = value.c_str();
    return 0;
}

} // namespace

std::string BodiesFile::attribute(const std::string &name) const {
    const auto it = attributes.find(name);
    return it == attributes.end() ? std::string() : it->second;
}

BodiesFile read_bodies_file(const std::string &path) {
    QuietErrors quiet;
    // Read-only without a lock: a running solver may still hold the file open for writing.
    Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_file_locking(access.get(), false, true);
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose);
    const Reader r{path, file.get()};
    if (file.get() < 0)
        r.fail("cannot open as HDF5 (no bodies record)");

    BodiesFile rec;
    std::vector<hsize_t> dims;
    rec.time = r.read<double>("/time", H5T_NATIVE_DOUBLE, dims);
    rec.unit = r.read<int>("/bodies/unit", H5T_NATIVE_INT, dims);
    const std::size_t steps = rec.time.size(), bodies = rec.unit.size();
    const auto vec = [](const double *v) { return Eigen::Vector3d(v[0], v[1], v[2]); };
    const auto quat = [](const double *q) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); };
    rec.position = r.series<Eigen::Vector3d>("/bodies/position", steps, bodies, 3, vec);
    rec.orientation = r.series<Eigen::Quaterniond>("/bodies/orientation", steps, bodies, 4, quat);
    rec.velocity = r.series<Eigen::Vector3d>("/bodies/velocity", steps, bodies, 3, vec);
    rec.angular_velocity = r.series<Eigen::Vector3d>("/bodies/angular_velocity", steps, bodies, 3, vec);
    rec.external_force = r.series<Eigen::Vector3d>("/bodies/external_force", steps, bodies, 3, vec);
    rec.external_torque = r.series<Eigen::Vector3d>("/bodies/external_torque", steps, bodies, 3, vec);
    rec.contact_force = r.series<Eigen::Vector3d>("/bodies/contact_force", steps, bodies, 3, vec);
    // A record read while its solver appends a step may hold it in /time and
    // not yet in every series: the last whole step ends it.
    rec.keep_steps(std::min({rec.position.size(), rec.orientation.size(), rec.velocity.size(),
                             rec.angular_velocity.size(), rec.external_force.size(),
                             rec.external_torque.size(), rec.contact_force.size()}));
    H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_string_attribute,
                &rec.attributes);
    return rec;
}

void BodiesFile::keep_steps(std::size_t steps) {
    if (steps >= time.size())
        return;
    time.resize(steps);
    for (auto *series :
         {&position, &velocity, &angular_velocity, &external_force, &external_torque, &contact_force})
        series->resize(steps);
    orientation.resize(steps);
}

void BodiesFile::states_at(std::size_t step, std::vector<BodyState> &states) const {
    states.resize(bodies());
    for (std::size_t b = 0; b < bodies(); ++b) {
        states[b].pose.position = position[step][b];
        states[b].pose.orientation = orientation[step][b];
        states[b].velocity = velocity[step][b];
        states[b].angular_velocity = angular_velocity[step][b];
        states[b].external_force = external_force[step][b];
        states[b].external_torque = external_torque[step][b];
        states[b].contact_force = contact_force[step][b];
    }
}

} // namespace armour
