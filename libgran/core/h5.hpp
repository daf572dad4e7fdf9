#pragma once

// Thin RAII wrapper over the HDF5 C API: just enough to write simulation results that h5py reads
// natively (native numeric types, variable-length UTF-8 strings) and to read them back for tests
// and resume. Every failure becomes a gran::h5::Error naming the file, object and operation.

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gran::h5 {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

namespace detail {

// Owns one reference to an HDF5 identifier. hid_t is int64_t since HDF5 1.10 (checked in h5.cpp);
// spelling it std::int64_t keeps hdf5.h and its macros out of every file including this header.
// Copies take another reference, so a copied Group stays valid on its own.
class Handle {
  public:
    Handle() = default;
    explicit Handle(std::int64_t id) noexcept : id_(id) {}
    Handle(const Handle& other) noexcept;
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)) {}
    Handle& operator=(Handle other) noexcept {
        std::swap(id_, other.id_);
        return *this;
    }
    ~Handle() { reset(); }

    std::int64_t get() const noexcept { return id_; }
    bool valid() const noexcept { return id_ >= 0; }
    std::int64_t release() noexcept { return std::exchange(id_, -1); }
    void reset() noexcept;  // drops the reference with the close call matching the id's type

  private:
    std::int64_t id_ = -1;
};

}  // namespace detail

class Group;
class Appendable;

// Why `name` cannot be one component of an HDF5 path (a '/' would nest groups, "." is the group
// itself, control characters do not survive every tool), or "" when it can. Names the user gives
// (species, drivers, observables) become result groups and are checked with this at load.
std::string name_problem(const std::string& name);

class File {
  public:
    static File create(const std::string& path);      // truncates an existing file
    static File open_read(const std::string& path);   // read-only
    static File open_write(const std::string& path);  // read and write an existing file
    // A file that lives in memory only (HDF5's core driver, no backing store): `name` names it
    // in messages. For results looked at and thrown away (a run's error bars mid-run).
    static File in_memory(const std::string& name);

    File(File&&) noexcept = default;
    File& operator=(File&&) noexcept = default;
    File(const File&) = delete;
    File& operator=(const File&) = delete;
    ~File() = default;  // the handle closes the file

    Group root() const;
    void flush();
    // Groups, datasets and attributes of this file still open somewhere (each Group, Appendable
    // and copy holds one): a file is only complete on disk once they are all closed.
    std::size_t open_objects() const;
    // Idempotent. HDF5 keeps the file open until Groups obtained from it are destroyed too.
    void close();

  private:
    File(detail::Handle id, std::string path) : id_(std::move(id)), path_(std::move(path)) {}

    detail::Handle id_;
    std::string path_;
};

// A group in an open file. Names are relative to this group (or absolute when they start with
// '/') and may be nested ("a/b/x"); missing intermediate groups are created on write.
class Group {
  public:
    Group group(const std::string& path);  // create or open
    bool exists(const std::string& path) const;
    const std::string& path() const { return path_; }  // absolute, e.g. "/observables/t"

    // Datasets. Empty dims => 1D of data.size(); otherwise product(dims) must equal data.size().
    // Writing an existing name replaces it, so results can be rewritten.
    void write(const std::string& name, std::span<const double> data,
               std::vector<std::size_t> dims = {});
    void write(const std::string& name, std::span<const std::int64_t> data,
               std::vector<std::size_t> dims = {});
    void write(const std::string& name, std::span<const std::uint64_t> data,
               std::vector<std::size_t> dims = {});
    void write_scalar(const std::string& name, double value);
    void write_scalar(const std::string& name, std::int64_t value);
    // Other integer types (int, std::size_t, ...) would be ambiguous between double and int64.
    template <std::integral T>
    void write_scalar(const std::string& name, T value) {
        write_scalar(name, static_cast<std::int64_t>(value));
    }
    // A dataset grown one row at a time (first dimension unlimited, chunked), e.g. frames or time
    // series written while a run goes on; row_shape {} makes a 1D series of scalars. Element types:
    // double and std::int64_t. Replaces an existing object of that name.
    template <class T>
    Appendable appendable(const std::string& name, std::vector<std::size_t> row_shape = {});
    void write_string(const std::string& name, const std::string& value);  // scalar vlen UTF-8
    // A link `name` to the object `object` (absolute) of the file `file`; a relative `file` is
    // looked for in this file's folder (where the trajectory sits beside its result).
    void external_link(const std::string& name, const std::string& file, const std::string& object);
    // A second name `name` for the existing object `target` (absolute, or relative to this group):
    // H5MD time series share one `step` and `time` this way.
    void hard_link(const std::string& name, const std::string& target);
    void write_strings(const std::string& name, const std::vector<std::string>& values);

    // Attributes on this group; an existing attribute of the same name is replaced.
    void attr(const std::string& name, double v);
    void attr(const std::string& name, std::int64_t v);
    template <std::integral T>
    void attr(const std::string& name, T v) {
        attr(name, static_cast<std::int64_t>(v));
    }
    void attr(const std::string& name, const std::string& v);  // vlen UTF-8, str in h5py
    void attr(const std::string& name, const char* v);
    void attr(const std::string& name, std::span<const double> v);
    void attr(const std::string& name, std::span<const std::int64_t> v);
    void attr(const std::string& name, const std::vector<std::string>& v);

    // Attributes on a dataset or subgroup of this group.
    void attr_on(const std::string& object, const std::string& name, double v);
    void attr_on(const std::string& object, const std::string& name, std::int64_t v);
    void attr_on(const std::string& object, const std::string& name, const std::string& v);

    // Reading (for tests and resume). Numeric reads convert from the stored type.
    std::vector<double> read_doubles(const std::string& name) const;
    std::vector<std::int64_t> read_int64s(const std::string& name) const;
    std::string read_string(const std::string& name) const;
    double read_attr_double(const std::string& name) const;
    std::string read_attr_string(const std::string& name) const;
    std::vector<std::size_t> shape(const std::string& name) const;  // {} for a scalar

    // Copies every object below `src` (datasets, groups, attributes) into this group under the
    // same names, e.g. to merge run files into one study file.
    void copy_children_from(const Group& src);

  private:
    friend class File;
    Group(detail::Handle id, std::string file, std::string path)
        : id_(std::move(id)), file_(std::move(file)), path_(std::move(path)) {}

    // "'/group/name' in file.h5" (or "'/group/name@attr' in file.h5"), for error messages.
    std::string where(const std::string& name, const std::string& attr = "") const;

    detail::Handle id_;
    std::string file_;
    std::string path_;  // absolute path of this group
};

// An open dataset with an unlimited first dimension (Group::appendable). append() extends it by
// whole rows and writes them at once: what was appended is in the file when it is flushed or
// closed.
class Appendable {
  public:
    // Move-only: a copy would count rows of its own and overwrite the other's.
    Appendable(Appendable&&) noexcept = default;
    Appendable& operator=(Appendable&&) noexcept = default;
    Appendable(const Appendable&) = delete;
    Appendable& operator=(const Appendable&) = delete;
    ~Appendable() = default;

    // `values` holds one or more whole rows (a multiple of row_size() values) of the dataset's
    // element type; anything else throws h5::Error.
    void append(std::span<const double> values);
    void append(std::span<const std::int64_t> values);
    std::size_t rows() const { return rows_; }
    std::size_t row_size() const { return row_size_; }

  private:
    friend class Group;
    Appendable(detail::Handle id, std::string where, bool is_double,
               std::vector<std::size_t> row_shape);
    void append_rows(const void* data, std::size_t count, bool is_double);

    detail::Handle id_;
    std::string where_;  // for error messages
    bool is_double_;
    std::vector<std::size_t> row_shape_;
    std::size_t row_size_ = 1;
    std::size_t rows_ = 0;
};

}  // namespace gran::h5
