// RAII for the HDF5 C API, shared by the writer (body_recorder.cpp) and the
// reader (analysis/bodies_file.cpp). Include it only from .cpp files: it
// brings in hdf5.h.
#pragma once

#include <hdf5.h>

namespace armour::hdf5 {

// Owns one HDF5 identifier; the closer matches its kind (file, dataset, ...).
class Handle {
  public:
    using Closer = herr_t (*)(hid_t);
    Handle() = default;
    Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
    Handle(Handle &&other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
    Handle &operator=(Handle &&other) noexcept {
        if (this != &other) {
            reset();
            id_ = other.id_;
            closer_ = other.closer_;
            other.id_ = -1;
        }
        return *this;
    }
    Handle(const Handle &) = delete;
    Handle &operator=(const Handle &) = delete;
    ~Handle() { reset(); }

    hid_t get() const { return id_; }
    herr_t reset() {
        herr_t status = 0;
        if (id_ >= 0 && closer_ != nullptr)
            status = closer_(id_);
        id_ = -1;
        return status;
    }

  private:
    hid_t id_ = -1;
    Closer closer_ = nullptr;
};

// HDF5 prints its whole error stack to stderr by default; we report one line
// through an exception instead, and put the caller's handler back afterwards
// so other HDF5 users in the process keep their own setting.
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

} // namespace armour::hdf5
