#include "libgran/core/h5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <functional>
#include <numeric>
#include <type_traits>

#include "libgran/core/file_lock.hpp"

namespace gran::h5 {

static_assert(std::is_same_v<hid_t, std::int64_t>, "detail::Handle stores hid_t as std::int64_t");

namespace detail {

Handle::Handle(const Handle& other) noexcept : id_(other.id_) {
    if (valid() && H5Iinc_ref(id_) < 0) id_ = -1;
}

void Handle::reset() noexcept {
    if (!valid()) return;
    // Each kind of identifier has its own close call; the wrong one fails and leaks the id.
    switch (H5Iget_type(id_)) {
        case H5I_FILE:
            H5Fclose(id_);
            break;
        case H5I_GROUP:
            H5Gclose(id_);
            break;
        case H5I_DATASET:
            H5Dclose(id_);
            break;
        case H5I_DATASPACE:
            H5Sclose(id_);
            break;
        case H5I_DATATYPE:
            H5Tclose(id_);
            break;
        case H5I_ATTR:
            H5Aclose(id_);
            break;
        case H5I_GENPROP_LST:
            H5Pclose(id_);
            break;
        default:
            break;  // H5I_BADID: already gone (e.g. the library was shut down)
    }
    id_ = -1;
}

}  // namespace detail

namespace {

using detail::Handle;

// HDF5's exit handler closes the files still open at exit; after a failed close (a full disk)
// it crashes there (SIGSEGV in H5F__close_cb, HDF5 1.10), turning a reported error into exit 139.
// Every file this program writes is closed explicitly, and one still open at exit is the .part of
// a failed run, so the handler is not needed. H5dont_atexit must precede every other HDF5 call:
// a static initialiser of this file runs before main.
const bool hdf5_without_exit_handler = H5dont_atexit() >= 0;

// HDF5 prints its whole error stack to stderr on every failure, including expected ones such as
// opening a missing file; we report failures as exceptions instead. The setting is per thread in
// this thread-safe build, so it is applied once per thread on the ways into a file.
void silence_hdf5_errors() {
    thread_local const bool silenced = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
    static_cast<void>(silenced);
}

// The innermost HDF5 error description (e.g. "unable to open file: ... errno = 2"), which says
// far more than the failing API call. Must run before any other HDF5 call resets the stack.
std::string hdf5_reason() {
    std::string reason;
    H5Ewalk2(
        H5E_DEFAULT, H5E_WALK_UPWARD,
        [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
            if (n == 0 && err->desc != nullptr) *static_cast<std::string*>(out) = err->desc;
            return 0;
        },
        &reason);
    // A failed write describes itself at length ("file write failed: time = ...\n, filename =
    // ..., errno = 28, error message = 'No space left on device', buf = ..."): the operating
    // system's message is the cause a user can act on.
    const std::string key = "error message = '";
    if (const auto at = reason.find(key); at != std::string::npos) {
        const auto end = reason.find('\'', at + key.size());
        if (end != std::string::npos) return reason.substr(at + key.size(), end - at - key.size());
    }
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    return reason;
}

[[noreturn]] void fail(const std::string& what) {
    const std::string reason = hdf5_reason();
    throw Error("h5: " + what + (reason.empty() ? "" : " (" + reason + ")"));
}

void check(herr_t status, const char* op, const std::string& where) {
    if (status < 0) fail(std::string("cannot ") + op + " " + where);
}

Handle own(hid_t id, const char* op, const std::string& where) {
    if (id < 0) fail(std::string("cannot ") + op + " " + where);
    return Handle(id);
}

Handle make_space(const std::vector<hsize_t>& dims, const std::string& where) {
    if (dims.empty()) return own(H5Screate(H5S_SCALAR), "create dataspace for", where);
    return own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
               "create dataspace for", where);
}

// Variable-length UTF-8 C string, used both in memory and in the file: h5py reads it as str.
Handle vlen_string_type(const std::string& where) {
    Handle type = own(H5Tcopy(H5T_C_S1), "create string type for", where);
    check(H5Tset_size(type.get(), H5T_VARIABLE), "create string type for", where);
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "create string type for", where);
    return type;
}

// Absolute path of `name` relative to the group at absolute path `base`, for error messages.
std::string join(const std::string& base, const std::string& name) {
    std::string full =
        name.starts_with('/') ? name : (base.ends_with('/') ? base : base + "/") + name;
    while (full.size() > 1 && full.ends_with('/')) full.pop_back();
    return full;
}

std::vector<const char*> c_strings(const std::vector<std::string>& values) {
    std::vector<const char*> out;
    out.reserve(values.size());
    for (const auto& v : values) out.push_back(v.c_str());
    return out;
}

std::vector<hsize_t> array_dims(std::size_t count, const std::vector<std::size_t>& dims,
                                const std::string& where) {
    if (dims.empty()) return {count};
    const std::size_t product =
        std::accumulate(dims.begin(), dims.end(), std::size_t{1}, std::multiplies<>{});
    if (product != count) {
        throw Error("h5: cannot write " + where + ": shape holds " + std::to_string(product) +
                    " values but " + std::to_string(count) + " were given");
    }
    return {dims.begin(), dims.end()};
}

// Creates intermediate groups so nested names like "a/b/x" work without creating "a/b" first.
Handle nested_link_props(const std::string& where) {
    Handle lcpl = own(H5Pcreate(H5P_LINK_CREATE), "create link properties for", where);
    check(H5Pset_create_intermediate_group(lcpl.get(), 1), "create link properties for", where);
    return lcpl;
}

bool link_exists(hid_t loc, const std::string& path) {
    // H5Lexists fails (rather than returning false) when an intermediate component is missing,
    // so walk the path one component at a time.
    std::string prefix = path.starts_with('/') ? "/" : "";
    std::size_t begin = 0;
    bool any = false;
    while (begin <= path.size()) {
        std::size_t end = path.find('/', begin);
        if (end == std::string::npos) end = path.size();
        if (end > begin) {
            if (any && !prefix.ends_with('/')) prefix += '/';
            prefix += path.substr(begin, end - begin);
            any = true;
            if (H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
        }
        begin = end + 1;
    }
    return any;
}

// Replaces any existing object of that name: HDF5 datasets cannot change type or extent in place.
// (The old dataset's space is not reclaimed inside the file; h5repack would do that.)
void write_dataset(hid_t loc, const std::string& name, hid_t type, const std::vector<hsize_t>& dims,
                   const void* data, const std::string& where) {
    if (link_exists(loc, name)) check(H5Ldelete(loc, name.c_str(), H5P_DEFAULT), "replace", where);
    const Handle space = make_space(dims, where);
    const Handle lcpl = nested_link_props(where);
    const Handle dset =
        own(H5Dcreate2(loc, name.c_str(), type, space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create dataset", where);
    // H5Dwrite rejects a null buffer even when there is nothing to write (empty vectors).
    const bool empty = !dims.empty() && std::accumulate(dims.begin(), dims.end(), hsize_t{1},
                                                        std::multiplies<>{}) == 0;
    if (!empty) {
        check(H5Dwrite(dset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write dataset",
              where);
    }
}

// Attributes cannot change type or extent in place either, so overwrite = delete + create.
void write_attr(hid_t obj, const std::string& name, hid_t type, const std::vector<hsize_t>& dims,
                const void* data, const std::string& where) {
    const htri_t present = H5Aexists(obj, name.c_str());
    check(present, "check attribute", where);
    if (present > 0) check(H5Adelete(obj, name.c_str()), "replace attribute", where);
    const Handle space = make_space(dims, where);
    const Handle attr =
        own(H5Acreate2(obj, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute", where);
    if (dims.empty() || dims[0] > 0)
        check(H5Awrite(attr.get(), type, data), "write attribute", where);
}

void write_string_attr(hid_t obj, const std::string& name, const std::string& value,
                       const std::string& where) {
    const Handle type = vlen_string_type(where);
    const char* c = value.c_str();
    write_attr(obj, name, type.get(), {}, &c, where);
}

// Chunks of about this many bytes (at least one row): large enough for few chunk headers, small
// enough for HDF5's default 1 MiB chunk cache.
constexpr std::size_t kChunkBytes = 64 * 1024;

Handle create_appendable(hid_t loc, const std::string& name, hid_t type,
                         const std::vector<std::size_t>& row_shape, const std::string& where) {
    std::size_t row = 1;
    for (const std::size_t d : row_shape) row *= d;
    if (row == 0) throw Error("h5: cannot create " + where + ": a row holds no values");
    if (link_exists(loc, name)) check(H5Ldelete(loc, name.c_str(), H5P_DEFAULT), "replace", where);
    std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED};
    std::vector<hsize_t> chunk{std::max<hsize_t>(1, kChunkBytes / (row * H5Tget_size(type)))};
    for (const std::size_t d : row_shape) {
        dims.push_back(d);
        max_dims.push_back(d);
        chunk.push_back(d);
    }
    const int rank = static_cast<int>(dims.size());
    const Handle space =
        own(H5Screate_simple(rank, dims.data(), max_dims.data()), "create dataspace for", where);
    const Handle dcpl = own(H5Pcreate(H5P_DATASET_CREATE), "create dataset properties for", where);
    check(H5Pset_chunk(dcpl.get(), rank, chunk.data()), "set the chunks of", where);
    const Handle lcpl = nested_link_props(where);
    return own(
        H5Dcreate2(loc, name.c_str(), type, space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT),
        "create dataset", where);
}

std::size_t point_count(hid_t space, const std::string& where) {
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    if (n < 0) fail("cannot get size of " + where);
    return static_cast<std::size_t>(n);
}

template <class T>
std::vector<T> read_dataset(hid_t loc, const std::string& name, hid_t mem_type,
                            const std::string& where) {
    const Handle dset = own(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset", where);
    const Handle space = own(H5Dget_space(dset.get()), "get dataspace of", where);
    std::vector<T> out(point_count(space.get(), where));
    if (!out.empty()) {
        check(H5Dread(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
              "read dataset", where);
    }
    return out;
}

// Reads a single string stored either as vlen (what we and h5py write) or fixed-length (what
// numpy byte strings become). `read(mem_type, buffer)` is H5Dread or H5Aread on the object.
std::string read_one_string(hid_t file_type, hid_t space, const std::string& where,
                            const std::function<herr_t(hid_t, void*)>& read) {
    if (H5Tget_class(file_type) != H5T_STRING) throw Error("h5: " + where + " is not a string");
    if (point_count(space, where) != 1) throw Error("h5: " + where + " is not a single string");
    const Handle mem_type = own(H5Tcopy(file_type), "copy string type of", where);
    const htri_t is_vlen = H5Tis_variable_str(file_type);
    check(is_vlen, "inspect string type of", where);
    if (is_vlen > 0) {
        char* c = nullptr;
        check(read(mem_type.get(), &c), "read", where);
        std::string value = c != nullptr ? c : "";
        H5Dvlen_reclaim(mem_type.get(), space, H5P_DEFAULT, &c);
        return value;
    }
    std::string value(H5Tget_size(file_type), '\0');
    check(read(mem_type.get(), value.data()), "read", where);
    return value.substr(0, value.find('\0'));  // NUL-padded or NUL-terminated
}

}  // namespace

std::string name_problem(const std::string& name) {
    if (name.empty()) return "an empty name";
    if (name == "." || name == "..") return "'" + name + "' is reserved";
    if (name.find('/') != std::string::npos)
        return "'/' separates groups in the result file; use another character such as '_'";
    for (const char c : name) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            return "a control character (tab, newline, ...) is not allowed";
    }
    return "";
}

// ---- File -------------------------------------------------------------------------------------

namespace {

// HDF5 opens a file it creates with O_TRUNC and only then takes its lock (flock), so creating a
// file another process is writing empties it under that writer, and the writer's file is then
// corrupt (two merges of one study did it: docs/cluster.md). Its lock is probed first instead.
// Without HDF5's file locking (HDF5_USE_FILE_LOCKING=FALSE) there is nothing to see.
void refuse_file_in_use(const std::string& path) {
    if (file_locked_by_another(path)) {
        throw Error("h5: cannot create file '" + path +
                    "': another process has it open (a second run or merge writing the same "
                    "file?); it was left as it is");
    }
}

}  // namespace

File File::create(const std::string& path) {
    silence_hdf5_errors();
    refuse_file_in_use(path);
    const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    return File(own(id, "create file", "'" + path + "'"), path);
}

File File::in_memory(const std::string& name) {
    silence_hdf5_errors();
    detail::Handle fapl = own(H5Pcreate(H5P_FILE_ACCESS), "create file access list for", name);
    check(H5Pset_fapl_core(fapl.get(), 1 << 20, 0), "use the core driver for", name);
    const hid_t id = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
    return File(own(id, "create in-memory file", "'" + name + "'"), name);
}

File File::open_read(const std::string& path) {
    silence_hdf5_errors();
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    return File(own(id, "open file for reading", "'" + path + "'"), path);
}

File File::open_write(const std::string& path) {
    silence_hdf5_errors();
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    return File(own(id, "open file for writing", "'" + path + "'"), path);
}

Group File::root() const {
    silence_hdf5_errors();
    if (!id_.valid()) throw Error("h5: file '" + path_ + "' is closed");
    return Group(
        own(H5Gopen2(id_.get(), "/", H5P_DEFAULT), "open root group of", "'" + path_ + "'"), path_,
        "/");
}

void File::flush() {
    if (!id_.valid()) throw Error("h5: file '" + path_ + "' is closed");
    check(H5Fflush(id_.get(), H5F_SCOPE_LOCAL), "flush file", "'" + path_ + "'");
}

std::size_t File::open_objects() const {
    if (!id_.valid()) return 0;
    const ssize_t n =
        H5Fget_obj_count(id_.get(), H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE |
                                        H5F_OBJ_ATTR | H5F_OBJ_LOCAL);
    if (n < 0) fail("cannot count the open objects of '" + path_ + "'");
    return static_cast<std::size_t>(n);
}

void File::close() {
    if (!id_.valid()) return;
    // Released first so a failed close is not retried by the destructor.
    check(H5Fclose(static_cast<hid_t>(id_.release())), "close file", "'" + path_ + "'");
}

// ---- Group ------------------------------------------------------------------------------------

std::string Group::where(const std::string& name, const std::string& attr) const {
    return "'" + join(path_, name) + (attr.empty() ? "" : "@" + attr) + "' in " + file_;
}

Group Group::group(const std::string& path) {
    silence_hdf5_errors();
    const std::string w = where(path);
    Handle g;
    if (exists(path)) {
        g = own(H5Gopen2(id_.get(), path.c_str(), H5P_DEFAULT), "open group", w);
    } else {
        const Handle lcpl = nested_link_props(w);
        g = own(H5Gcreate2(id_.get(), path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                "create group", w);
    }
    return Group(std::move(g), file_, join(path_, path));
}

bool Group::exists(const std::string& path) const {
    return link_exists(id_.get(), path);
}

void Group::write(const std::string& name, std::span<const double> data,
                  std::vector<std::size_t> dims) {
    const std::string w = where(name);
    write_dataset(id_.get(), name, H5T_NATIVE_DOUBLE, array_dims(data.size(), dims, w), data.data(),
                  w);
}

void Group::write(const std::string& name, std::span<const std::int64_t> data,
                  std::vector<std::size_t> dims) {
    const std::string w = where(name);
    write_dataset(id_.get(), name, H5T_NATIVE_INT64, array_dims(data.size(), dims, w), data.data(),
                  w);
}

void Group::write(const std::string& name, std::span<const std::uint64_t> data,
                  std::vector<std::size_t> dims) {
    const std::string w = where(name);
    write_dataset(id_.get(), name, H5T_NATIVE_UINT64, array_dims(data.size(), dims, w), data.data(),
                  w);
}

void Group::write_scalar(const std::string& name, double value) {
    write_dataset(id_.get(), name, H5T_NATIVE_DOUBLE, {}, &value, where(name));
}

void Group::write_scalar(const std::string& name, std::int64_t value) {
    write_dataset(id_.get(), name, H5T_NATIVE_INT64, {}, &value, where(name));
}

template <class T>
Appendable Group::appendable(const std::string& name, std::vector<std::size_t> row_shape) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>,
                  "appendable datasets hold double or std::int64_t");
    const std::string w = where(name);
    constexpr bool is_double = std::is_same_v<T, double>;
    Handle dset = create_appendable(id_.get(), name,
                                    is_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, row_shape, w);
    return Appendable(std::move(dset), w, is_double, std::move(row_shape));
}

template Appendable Group::appendable<double>(const std::string&, std::vector<std::size_t>);
template Appendable Group::appendable<std::int64_t>(const std::string&, std::vector<std::size_t>);

void Group::write_string(const std::string& name, const std::string& value) {
    const std::string w = where(name);
    const Handle type = vlen_string_type(w);
    const char* c = value.c_str();
    write_dataset(id_.get(), name, type.get(), {}, &c, w);
}

void Group::write_strings(const std::string& name, const std::vector<std::string>& values) {
    const std::string w = where(name);
    const Handle type = vlen_string_type(w);
    const std::vector<const char*> cs = c_strings(values);
    write_dataset(id_.get(), name, type.get(), {values.size()}, cs.data(), w);
}

void Group::attr(const std::string& name, double v) {
    write_attr(id_.get(), name, H5T_NATIVE_DOUBLE, {}, &v, where("", name));
}

void Group::attr(const std::string& name, std::int64_t v) {
    write_attr(id_.get(), name, H5T_NATIVE_INT64, {}, &v, where("", name));
}

void Group::attr(const std::string& name, const std::string& v) {
    write_string_attr(id_.get(), name, v, where("", name));
}

void Group::attr(const std::string& name, const char* v) {
    attr(name, std::string(v));
}

void Group::attr(const std::string& name, std::span<const double> v) {
    write_attr(id_.get(), name, H5T_NATIVE_DOUBLE, {v.size()}, v.data(), where("", name));
}

void Group::attr(const std::string& name, std::span<const std::int64_t> v) {
    write_attr(id_.get(), name, H5T_NATIVE_INT64, {v.size()}, v.data(), where("", name));
}

void Group::attr(const std::string& name, const std::vector<std::string>& v) {
    const std::string w = where("", name);
    const Handle type = vlen_string_type(w);
    const std::vector<const char*> cs = c_strings(v);
    write_attr(id_.get(), name, type.get(), {v.size()}, cs.data(), w);
}

void Group::attr_on(const std::string& object, const std::string& name, double v) {
    const std::string w = where(object, name);
    const Handle obj = own(H5Oopen(id_.get(), object.c_str(), H5P_DEFAULT), "open object for", w);
    write_attr(obj.get(), name, H5T_NATIVE_DOUBLE, {}, &v, w);
}

void Group::attr_on(const std::string& object, const std::string& name, std::int64_t v) {
    const std::string w = where(object, name);
    const Handle obj = own(H5Oopen(id_.get(), object.c_str(), H5P_DEFAULT), "open object for", w);
    write_attr(obj.get(), name, H5T_NATIVE_INT64, {}, &v, w);
}

void Group::attr_on(const std::string& object, const std::string& name, const std::string& v) {
    const std::string w = where(object, name);
    const Handle obj = own(H5Oopen(id_.get(), object.c_str(), H5P_DEFAULT), "open object for", w);
    write_string_attr(obj.get(), name, v, w);
}

std::vector<double> Group::read_doubles(const std::string& name) const {
    return read_dataset<double>(id_.get(), name, H5T_NATIVE_DOUBLE, where(name));
}

std::vector<std::int64_t> Group::read_int64s(const std::string& name) const {
    return read_dataset<std::int64_t>(id_.get(), name, H5T_NATIVE_INT64, where(name));
}

std::string Group::read_string(const std::string& name) const {
    const std::string w = where(name);
    const Handle dset = own(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT), "open dataset", w);
    const Handle type = own(H5Dget_type(dset.get()), "get type of", w);
    const Handle space = own(H5Dget_space(dset.get()), "get dataspace of", w);
    return read_one_string(type.get(), space.get(), w, [&](hid_t mem_type, void* buf) {
        return H5Dread(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
    });
}

double Group::read_attr_double(const std::string& name) const {
    const std::string w = where("", name);
    const Handle attr = own(H5Aopen(id_.get(), name.c_str(), H5P_DEFAULT), "open attribute", w);
    const Handle space = own(H5Aget_space(attr.get()), "get dataspace of", w);
    if (point_count(space.get(), w) != 1) throw Error("h5: " + w + " is not a single value");
    double value = 0.0;
    check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), "read attribute", w);
    return value;
}

std::string Group::read_attr_string(const std::string& name) const {
    const std::string w = where("", name);
    const Handle attr = own(H5Aopen(id_.get(), name.c_str(), H5P_DEFAULT), "open attribute", w);
    const Handle type = own(H5Aget_type(attr.get()), "get type of", w);
    const Handle space = own(H5Aget_space(attr.get()), "get dataspace of", w);
    return read_one_string(type.get(), space.get(), w, [&](hid_t mem_type, void* buf) {
        return H5Aread(attr.get(), mem_type, buf);
    });
}

void Group::hard_link(const std::string& name, const std::string& target) {
    const std::string w = where(name);
    if (link_exists(id_.get(), name))
        check(H5Ldelete(id_.get(), name.c_str(), H5P_DEFAULT), "replace", w);
    const Handle lcpl = nested_link_props(w);
    check(
        H5Lcreate_hard(id_.get(), target.c_str(), id_.get(), name.c_str(), lcpl.get(), H5P_DEFAULT),
        "create a link to", target + " as " + w);
}

void Group::external_link(const std::string& name, const std::string& file,
                          const std::string& object) {
    const std::string w = where(name);
    if (link_exists(id_.get(), name))
        check(H5Ldelete(id_.get(), name.c_str(), H5P_DEFAULT), "replace", w);
    const Handle lcpl = nested_link_props(w);
    check(H5Lcreate_external(file.c_str(), object.c_str(), id_.get(), name.c_str(), lcpl.get(),
                             H5P_DEFAULT),
          "create external link", w);
}

std::vector<std::size_t> Group::shape(const std::string& name) const {
    const std::string w = where(name);
    const Handle dset = own(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT), "open dataset", w);
    const Handle space = own(H5Dget_space(dset.get()), "get dataspace of", w);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) fail("cannot get rank of " + w);
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), "get shape of", w);
    return {dims.begin(), dims.end()};
}

void Group::copy_children_from(const Group& src) {
    silence_hdf5_errors();
    std::vector<std::string> names;
    check(H5Literate(
              src.id_.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
              [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
                  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
                  return 0;
              },
              &names),
          "list", src.where(""));
    for (const auto& n : names) {
        check(H5Ocopy(src.id_.get(), n.c_str(), id_.get(), n.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              "copy", src.where(n) + " into " + where(n));
    }
}

// ---- Appendable -------------------------------------------------------------------------------

Appendable::Appendable(Handle id, std::string where, bool is_double,
                       std::vector<std::size_t> row_shape)
    : id_(std::move(id)),
      where_(std::move(where)),
      is_double_(is_double),
      row_shape_(std::move(row_shape)) {
    for (const std::size_t d : row_shape_) row_size_ *= d;
}

void Appendable::append(std::span<const double> values) {
    append_rows(values.data(), values.size(), true);
}

void Appendable::append(std::span<const std::int64_t> values) {
    append_rows(values.data(), values.size(), false);
}

void Appendable::append_rows(const void* data, std::size_t count, bool is_double) {
    if (is_double != is_double_) {
        throw Error(std::string("h5: cannot append ") + (is_double ? "doubles" : "integers") +
                    " to " + where_ + ", which holds " + (is_double_ ? "doubles" : "integers"));
    }
    if (count % row_size_ != 0) {
        throw Error("h5: cannot append " + std::to_string(count) + " values to " + where_ +
                    ": rows hold " + std::to_string(row_size_));
    }
    const std::size_t k = count / row_size_;
    if (k == 0) return;
    std::vector<hsize_t> dims{rows_ + k};
    dims.insert(dims.end(), row_shape_.begin(), row_shape_.end());
    check(H5Dset_extent(id_.get(), dims.data()), "extend", where_);
    const Handle file_space = own(H5Dget_space(id_.get()), "get dataspace of", where_);
    std::vector<hsize_t> start(dims.size(), 0), block = dims;
    start[0] = rows_;
    block[0] = k;
    check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, block.data(),
                              nullptr),
          "select the new rows of", where_);
    const Handle memory = make_space(block, where_);
    check(H5Dwrite(id_.get(), is_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, memory.get(),
                   file_space.get(), H5P_DEFAULT, data),
          "append to", where_);
    rows_ += k;
}

}  // namespace gran::h5
