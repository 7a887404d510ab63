#include "bodies_file.h"

#include "mesh.h"

#include <hdf5.h>

#include <functional>

namespace armour {
namespace {

// Closes one HDF5 identifier when it goes out of scope.
struct Id {
    hid_t id;
    herr_t (*close)(hid_t);
    Id(hid_t value, herr_t (*closer)(hid_t)) : id(value), close(closer) {}
    ~Id() {
        if (id >= 0)
            close(id);
    }
    Id(const Id &) = delete;
    Id &operator=(const Id &) = delete;
};

// HDF5 prints its error stack by default; a missing dataset is reported
// here as one line instead. The caller's handler is put back afterwards.
class QuietErrors {
  public:
    QuietErrors() {
        H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    }
    ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
    QuietErrors(const QuietErrors &) = delete;
    QuietErrors &operator=(const QuietErrors &) = delete;

  private:
    H5E_auto2_t func_ = nullptr;
    void *data_ = nullptr;
};

struct Reader {
    std::string path;
    hid_t file;

    [[noreturn]] void fail(const std::string &what) const { throw InputError(path + ": " + what); }

    // All values of a dataset in storage order, converted to T, and its extents.
    template <class T>
    std::vector<T> read(const std::string &name, hid_t memory_type, std::vector<hsize_t> &dims) const {
        if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
            fail("no dataset " + name);
        Id set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
        if (set.id < 0)
            fail("cannot open dataset " + name);
        Id space(H5Dget_space(set.id), H5Sclose);
        const int rank = H5Sget_simple_extent_ndims(space.id);
        dims.assign(static_cast<std::size_t>(std::max(rank, 0)), 0);
        H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
        hsize_t count = 1;
        for (const hsize_t d : dims)
            count *= d;
        std::vector<T> data(count);
        if (count > 0 && H5Dread(set.id, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
            fail("cannot read dataset " + name);
        return data;
    }

    // A (steps, bodies, width) dataset, each row made into an Eigen value by `make`.
    template <class T>
    BodiesFile::Series<T> series(const std::string &name, std::size_t steps, std::size_t bodies,
                                 std::size_t width, const std::function<T(const double *)> &make) const {
        std::vector<hsize_t> dims;
        const std::vector<double> data = read<double>(name, H5T_NATIVE_DOUBLE, dims);
        if (dims.size() != 3 || dims[0] != steps || dims[1] != bodies || dims[2] != width)
            fail(name + " is not (" + std::to_string(steps) + ", " + std::to_string(bodies) + ", " +
                 std::to_string(width) + ")");
        BodiesFile::Series<T> out(steps);
        for (std::size_t s = 0; s < steps; ++s)
            for (std::size_t b = 0; b < bodies; ++b)
                out[s].push_back(make(&data[width * (s * bodies + b)]));
        return out;
    }
};

herr_t collect_string_attribute(hid_t object, const char *name, const H5A_info_t *, void *client) {
    Id attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
    Id type(H5Aget_type(attribute.id), H5Tclose);
    if (attribute.id < 0 || type.id < 0 || H5Tget_class(type.id) != H5T_STRING ||
        H5Tis_variable_str(type.id) > 0)
        return 0; // the recorder writes fixed-length strings only
    std::string value(H5Tget_size(type.id), '\0');
    if (H5Aread(attribute.id, type.id, value.data()) >= 0)
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
    Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_file_locking(access.id, false, true);
    Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.id), H5Fclose);
    const Reader r{path, file.id};
    if (file.id < 0)
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
    H5Aiterate2(file.id, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_string_attribute, &rec.attributes);
    return rec;
}

} // namespace armour
