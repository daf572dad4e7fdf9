#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::h5::Error;
using gran::h5::File;
using gran::h5::Group;

// Each test gets its own directory: ctest runs tests as parallel processes.
class H5Test : public gran::testing::TempDirTest {
  protected:
    H5Test() : TempDirTest("gran_h5") {}
};

class H5File : public H5Test {};
class H5Group : public H5Test {};

// The wrapper has no readers for some kinds (string lists, array attributes, stored types), so
// these go straight to the C API, the way h5py would see the file.
std::vector<std::string> raw_strings(hid_t obj_or_file, const std::string& object,
                                     const std::string& attr = "") {
    const hid_t obj = H5Oopen(obj_or_file, object.c_str(), H5P_DEFAULT);
    const hid_t a = attr.empty() ? -1 : H5Aopen(obj, attr.c_str(), H5P_DEFAULT);
    const hid_t type = attr.empty() ? H5Dget_type(obj) : H5Aget_type(a);
    const hid_t space = attr.empty() ? H5Dget_space(obj) : H5Aget_space(a);
    std::vector<char*> ptrs(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    EXPECT_EQ(H5Tget_cset(type), H5T_CSET_UTF8);
    EXPECT_GT(H5Tis_variable_str(type), 0);
    if (!ptrs.empty()) {
        attr.empty() ? H5Dread(obj, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data())
                     : H5Aread(a, type, ptrs.data());
    }
    std::vector<std::string> out(ptrs.begin(), ptrs.end());
    H5Dvlen_reclaim(type, space, H5P_DEFAULT, ptrs.data());
    H5Sclose(space);
    H5Tclose(type);
    if (a >= 0) H5Aclose(a);
    H5Oclose(obj);
    return out;
}

std::vector<double> raw_double_attr(hid_t file, const std::string& object,
                                    const std::string& attr) {
    const hid_t a = H5Aopen_by_name(file, object.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    const hid_t space = H5Aget_space(a);
    std::vector<double> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!out.empty()) H5Aread(a, H5T_NATIVE_DOUBLE, out.data());
    H5Sclose(space);
    H5Aclose(a);
    return out;
}

// Opens a file with the raw C API, independent of the wrapper under test.
struct RawFile {
    explicit RawFile(const std::string& path)
        : id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
    ~RawFile() { H5Fclose(id); }
    hid_t id;
};

// ---- File ---------------------------------------------------------------------------------

TEST_F(H5File, CreatedFileReopensReadOnly) {
    {
        File f = File::create(path("a.h5"));
        f.root().write_scalar("x", 1.5);
    }
    File f = File::open_read(path("a.h5"));
    EXPECT_EQ(f.root().read_doubles("x"), std::vector<double>{1.5});
}

TEST_F(H5File, OpeningMissingFileThrowsErrorNamingPath) {
    const std::string missing = path("missing.h5");
    try {
        File::open_read(missing);
        FAIL() << "expected gran::h5::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
}

TEST_F(H5File, OpeningNonHdf5FileThrowsError) {
    std::ofstream(path("text.h5")) << "not hdf5\n";
    EXPECT_THROW(File::open_read(path("text.h5")), Error);
}

TEST_F(H5File, CreatingInMissingDirectoryThrowsErrorNamingPath) {
    const std::string bad = path("no/such/dir/a.h5");
    try {
        File::create(bad);
        FAIL() << "expected gran::h5::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
}

TEST_F(H5File, CreateTruncatesExistingFile) {
    File::create(path("a.h5")).root().write_scalar("old", 1.0);
    File f = File::create(path("a.h5"));
    EXPECT_FALSE(f.root().exists("old"));
}

TEST_F(H5File, CloseIsIdempotentAndRootOfClosedFileThrows) {
    File f = File::create(path("a.h5"));
    f.root().write_scalar("x", 2.0);
    f.flush();
    f.close();
    f.close();
    EXPECT_THROW(f.root(), Error);
    EXPECT_THROW(f.flush(), Error);
    EXPECT_EQ(File::open_read(path("a.h5")).root().read_doubles("x"), std::vector<double>{2.0});
}

TEST_F(H5File, MovedFileStaysUsable) {
    File a = File::create(path("a.h5"));
    File b = std::move(a);
    b.root().write_scalar("x", 3.0);
    a = File::create(path("b.h5"));  // moved-from file can be reassigned
    a.root().write_scalar("y", 4.0);
    b.close();
    a.close();
    EXPECT_EQ(File::open_read(path("a.h5")).root().read_doubles("x"), std::vector<double>{3.0});
    EXPECT_EQ(File::open_read(path("b.h5")).root().read_doubles("y"), std::vector<double>{4.0});
}

TEST_F(H5File, ReadOnlyFileRejectsWrites) {
    File::create(path("a.h5")).root().write_scalar("x", 1.0);
    File f = File::open_read(path("a.h5"));
    Group root = f.root();
    EXPECT_THROW(root.write_scalar("y", 2.0), Error);
    EXPECT_THROW(root.attr("a", 1.0), Error);
}

// ---- Datasets -----------------------------------------------------------------------------

TEST_F(H5Group, RoundTripsDoubleDatasetAs1DByDefault) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    const std::vector<double> v{0.5, -1.25, 1e300, 0.0};
    root.write("v", v);
    EXPECT_EQ(root.read_doubles("v"), v);
    EXPECT_EQ(root.shape("v"), std::vector<std::size_t>{4});
}

TEST_F(H5Group, RoundTripsDoubleDatasetWithShape) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    const std::vector<double> v{1, 2, 3, 4, 5, 6};
    root.write("m", v, {2, 3});
    EXPECT_EQ(root.shape("m"), (std::vector<std::size_t>{2, 3}));
    EXPECT_EQ(root.read_doubles("m"), v);  // row-major, as numpy sees it
}

TEST_F(H5Group, RoundTripsInt64DatasetIncludingExtremes) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    const std::vector<std::int64_t> v{std::numeric_limits<std::int64_t>::min(), -1, 0,
                                      std::numeric_limits<std::int64_t>::max()};
    root.write("i", v, {2, 2});
    EXPECT_EQ(root.read_int64s("i"), v);
    EXPECT_EQ(root.shape("i"), (std::vector<std::size_t>{2, 2}));
}

TEST_F(H5Group, StoresUint64DatasetAsUnsigned64Bit) {
    const std::vector<std::uint64_t> v{0, 7, std::numeric_limits<std::uint64_t>::max()};
    {
        File f = File::create(path("a.h5"));
        f.root().write("u", v);
    }
    RawFile raw(path("a.h5"));
    const hid_t d = H5Dopen2(raw.id, "u", H5P_DEFAULT);
    const hid_t t = H5Dget_type(d);
    EXPECT_EQ(H5Tget_sign(t), H5T_SGN_NONE);
    EXPECT_EQ(H5Tget_size(t), 8u);
    std::vector<std::uint64_t> back(v.size());
    H5Dread(d, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data());
    EXPECT_EQ(back, v);
    H5Tclose(t);
    H5Dclose(d);
}

TEST_F(H5Group, ReadingConvertsBetweenNumericTypes) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("i", std::vector<std::int64_t>{1, -2});
    root.write("u", std::vector<std::uint64_t>{3, 4});
    EXPECT_EQ(root.read_doubles("i"), (std::vector<double>{1.0, -2.0}));
    EXPECT_EQ(root.read_int64s("u"), (std::vector<std::int64_t>{3, 4}));
}

TEST_F(H5Group, RoundTripsEmptyDataset) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("e", std::vector<double>{});
    root.write("e2", std::vector<double>{}, {0, 3});
    EXPECT_TRUE(root.read_doubles("e").empty());
    EXPECT_EQ(root.shape("e"), std::vector<std::size_t>{0});
    EXPECT_EQ(root.shape("e2"), (std::vector<std::size_t>{0, 3}));
}

TEST_F(H5Group, RejectsShapeThatDoesNotHoldTheData) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    EXPECT_THROW(root.write("m", std::vector<double>{1, 2, 3}, {2, 2}), Error);
    EXPECT_FALSE(root.exists("m"));
}

TEST_F(H5Group, RoundTripsScalarsWithEmptyShape) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write_scalar("d", 0.25);
    root.write_scalar("i", std::int64_t{-9});
    root.write_scalar("n", 42);                 // int goes through the int64 overload
    root.write_scalar("s", std::size_t{1000});  // so does size_t
    EXPECT_EQ(root.read_doubles("d"), std::vector<double>{0.25});
    EXPECT_EQ(root.read_int64s("i"), std::vector<std::int64_t>{-9});
    EXPECT_EQ(root.read_int64s("n"), std::vector<std::int64_t>{42});
    EXPECT_EQ(root.read_int64s("s"), std::vector<std::int64_t>{1000});
    EXPECT_TRUE(root.shape("d").empty());
}

TEST_F(H5Group, RoundTripsUtf8StringDataset) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write_string("s", "φ = 0.9 — inelastic");
    root.write_string("empty", "");
    EXPECT_EQ(root.read_string("s"), "φ = 0.9 — inelastic");
    EXPECT_EQ(root.read_string("empty"), "");
    EXPECT_TRUE(root.shape("s").empty());
}

TEST_F(H5Group, WritesStringListAs1DVlenUtf8) {
    {
        File f = File::create(path("a.h5"));
        Group root = f.root();
        root.write_strings("names", {"x", "", "θ"});
        root.write_strings("none", {});
        EXPECT_EQ(root.shape("names"), std::vector<std::size_t>{3});
    }
    RawFile raw(path("a.h5"));
    EXPECT_EQ(raw_strings(raw.id, "names"), (std::vector<std::string>{"x", "", "θ"}));
    EXPECT_TRUE(raw_strings(raw.id, "none").empty());
}

TEST_F(H5Group, OverwritingDatasetReplacesTypeAndShape) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("x", std::vector<double>{1, 2, 3});
    root.write("x", std::vector<std::int64_t>{4, 5, 6, 7}, {2, 2});
    EXPECT_EQ(root.read_int64s("x"), (std::vector<std::int64_t>{4, 5, 6, 7}));
    EXPECT_EQ(root.shape("x"), (std::vector<std::size_t>{2, 2}));
    root.write_string("x", "now text");
    EXPECT_EQ(root.read_string("x"), "now text");
}

// ---- Groups -------------------------------------------------------------------------------

TEST_F(H5Group, CreatesNestedGroupsAndReopensExistingOnes) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    Group c = root.group("a/b/c");
    c.write_scalar("x", 1.0);
    EXPECT_TRUE(root.exists("a"));
    EXPECT_TRUE(root.exists("a/b"));
    Group b = root.group("a/b");  // opens, does not recreate
    EXPECT_TRUE(b.exists("c/x"));
    EXPECT_EQ(b.group("c").read_doubles("x"), std::vector<double>{1.0});
}

TEST_F(H5Group, ExistsIsFalseForMissingIntermediates) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.group("a").write_scalar("x", 1.0);
    EXPECT_TRUE(root.exists("a/x"));
    EXPECT_TRUE(root.exists("/a/x"));
    EXPECT_FALSE(root.exists("a/y"));
    EXPECT_FALSE(root.exists("no/such/path"));
    EXPECT_FALSE(root.exists("a/x/below_dataset"));
}

TEST_F(H5Group, WritesDatasetUnderNestedNameCreatingGroups) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("run/0/energy", std::vector<double>{1.0, 0.5});
    EXPECT_EQ(root.group("run/0").read_doubles("energy"), (std::vector<double>{1.0, 0.5}));
}

TEST_F(H5Group, GroupOverExistingDatasetThrows) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write_scalar("x", 1.0);
    EXPECT_THROW(root.group("x"), Error);
}

TEST_F(H5Group, CopiedGroupOutlivesOriginal) {
    File f = File::create(path("a.h5"));
    Group copy = f.root();
    {
        Group g = f.root().group("g");
        copy = g;
    }
    copy.write_scalar("x", 5.0);
    EXPECT_EQ(f.root().read_doubles("g/x"), std::vector<double>{5.0});
}

// ---- Attributes ---------------------------------------------------------------------------

TEST_F(H5Group, RoundTripsScalarAttributesAndOverwritesThem) {
    File f = File::create(path("a.h5"));
    Group g = f.root().group("params");
    g.attr("dt", 1e-3);
    g.attr("steps", std::int64_t{100});
    g.attr("seed", 7);  // plain int
    g.attr("model", std::string("hard spheres"));
    g.attr("driver", "event-driven");
    EXPECT_EQ(g.read_attr_double("dt"), 1e-3);
    EXPECT_EQ(g.read_attr_double("steps"), 100.0);
    EXPECT_EQ(g.read_attr_double("seed"), 7.0);
    EXPECT_EQ(g.read_attr_string("model"), "hard spheres");
    EXPECT_EQ(g.read_attr_string("driver"), "event-driven");

    g.attr("dt", "now a string");  // overwriting may change the type
    EXPECT_EQ(g.read_attr_string("dt"), "now a string");
    g.attr("model", 2.5);
    EXPECT_EQ(g.read_attr_double("model"), 2.5);
}

TEST_F(H5Group, WritesArrayAndStringListAttributes) {
    {
        File f = File::create(path("a.h5"));
        Group root = f.root();
        root.attr("box", std::vector<double>{1.0, 2.0, 3.0});
        root.attr("counts", std::vector<std::int64_t>{4, 5});
        root.attr("species", std::vector<std::string>{"A", "βeta"});
        root.attr("no_values", std::vector<double>{});
    }
    RawFile raw(path("a.h5"));
    EXPECT_EQ(raw_double_attr(raw.id, "/", "box"), (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_EQ(raw_double_attr(raw.id, "/", "counts"), (std::vector<double>{4.0, 5.0}));
    EXPECT_EQ(raw_strings(raw.id, "/", "species"), (std::vector<std::string>{"A", "βeta"}));
    EXPECT_TRUE(raw_double_attr(raw.id, "/", "no_values").empty());
}

TEST_F(H5Group, WritesAttributesOnDatasetsAndSubgroups) {
    {
        File f = File::create(path("a.h5"));
        Group root = f.root();
        root.write("t", std::vector<double>{0, 1});
        root.group("sub");
        root.attr_on("t", "units", std::string("s"));
        root.attr_on("t", "scale", 2.0);
        root.attr_on("sub", "note", std::string("hello"));
        root.attr_on("t", "scale", 3.0);  // overwrite
        EXPECT_EQ(root.group("sub").read_attr_string("note"), "hello");
        EXPECT_THROW(root.attr_on("missing", "x", 1.0), Error);
    }
    RawFile raw(path("a.h5"));
    EXPECT_EQ(raw_strings(raw.id, "t", "units"), std::vector<std::string>{"s"});
    EXPECT_EQ(raw_double_attr(raw.id, "t", "scale"), std::vector<double>{3.0});
}

// ---- Errors -------------------------------------------------------------------------------

TEST_F(H5Group, ReadingMissingDatasetThrowsErrorNamingObjectAndFile) {
    File f = File::create(path("a.h5"));
    Group g = f.root().group("results");
    try {
        g.read_doubles("nope");
        FAIL() << "expected gran::h5::Error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("/results/nope"), std::string::npos) << msg;
        EXPECT_NE(msg.find(path("a.h5")), std::string::npos) << msg;
    }
    EXPECT_THROW(g.read_int64s("nope"), Error);
    EXPECT_THROW(g.read_string("nope"), Error);
    EXPECT_THROW(g.shape("nope"), Error);
    EXPECT_THROW(g.read_attr_double("nope"), Error);
    EXPECT_THROW(g.read_attr_string("nope"), Error);
}

TEST_F(H5Group, ReadingWrongKindThrows) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("v", std::vector<double>{1, 2});
    root.write_string("s", "text");
    root.attr("a", "text");
    root.attr("arr", std::vector<double>{1, 2});
    EXPECT_THROW(root.read_string("v"), Error);
    EXPECT_THROW(root.read_doubles("s"), Error);
    EXPECT_THROW(root.read_attr_double("a"), Error);
    EXPECT_THROW(root.read_attr_double("arr"), Error);  // not a single value
}

// ---- Appendable datasets ------------------------------------------------------------------

TEST_F(H5Group, AppendableGrowsByRowsAndReadsBack) {
    {
        File f = File::create(path("a.h5"));
        gran::h5::Appendable frames = f.root().appendable<double>("frames/value", {2, 3});
        EXPECT_EQ(frames.rows(), 0u);
        EXPECT_EQ(frames.row_size(), 6u);
        frames.append(std::vector<double>{1, 2, 3, 4, 5, 6});
        frames.append(std::vector<double>{7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18});  // two
        EXPECT_EQ(frames.rows(), 3u);
        gran::h5::Appendable step = f.root().appendable<std::int64_t>("frames/step");
        for (std::int64_t k = 0; k < 5; ++k) step.append(std::vector<std::int64_t>{k});
    }
    File f = File::open_read(path("a.h5"));
    const Group root = f.root();
    EXPECT_EQ(root.shape("frames/value"), (std::vector<std::size_t>{3, 2, 3}));
    std::vector<double> want(18);
    for (std::size_t k = 0; k < want.size(); ++k) want[k] = double(k + 1);
    EXPECT_EQ(root.read_doubles("frames/value"), want);
    EXPECT_EQ(root.read_int64s("frames/step"), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
}

TEST_F(H5Group, AppendableIsChunkedWithUnlimitedFirstDimension) {
    {
        File f = File::create(path("a.h5"));
        f.root().appendable<double>("x", {4}).append(std::vector<double>(8, 1.0));
    }
    RawFile raw(path("a.h5"));
    const hid_t d = H5Dopen2(raw.id, "x", H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    hsize_t dims[2], max_dims[2];
    ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, max_dims), 2);
    EXPECT_EQ(dims[0], 2u);
    EXPECT_EQ(max_dims[0], H5S_UNLIMITED);
    EXPECT_EQ(max_dims[1], 4u);
    const hid_t dcpl = H5Dget_create_plist(d);
    EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Dclose(d);
}

TEST_F(H5Group, AppendableRejectsPartialRowsAndOtherTypes) {
    File f = File::create(path("a.h5"));
    gran::h5::Appendable a = f.root().appendable<double>("x", {3});
    EXPECT_THROW(a.append(std::vector<double>{1, 2}), Error);
    EXPECT_THROW(a.append(std::vector<std::int64_t>{1, 2, 3}), Error);
    a.append(std::vector<double>{});  // no rows: nothing to do
    EXPECT_EQ(a.rows(), 0u);
    EXPECT_THROW(f.root().appendable<double>("y", {0}), Error);
}

TEST_F(H5Group, AppendableReplacesAnExistingDataset) {
    File f = File::create(path("a.h5"));
    Group root = f.root();
    root.write("x", std::vector<double>{1, 2, 3});
    root.appendable<std::int64_t>("x").append(std::vector<std::int64_t>{7});
    EXPECT_EQ(root.read_int64s("x"), std::vector<std::int64_t>{7});
}

TEST_F(H5File, CountsTheObjectsStillOpen) {
    File f = File::create(path("a.h5"));
    EXPECT_EQ(f.open_objects(), 0u);
    {
        Group g = f.root().group("g");
        gran::h5::Appendable a = g.appendable<double>("x");
        EXPECT_EQ(f.open_objects(), 2u);  // the group and the dataset
    }
    EXPECT_EQ(f.open_objects(), 0u);
    f.close();
    EXPECT_EQ(f.open_objects(), 0u);
}

// A file with every kind of content, for checking with external readers (h5py). Set
// GRAN_H5_KEEP_FILE to a path to keep it there.
TEST_F(H5Group, WritesEveryKindIntoOneFile) {
    const char* keep = std::getenv("GRAN_H5_KEEP_FILE");
    const std::string file = keep != nullptr ? keep : path("all.h5");
    {
        File f = File::create(file);
        Group root = f.root();
        root.attr("title", "gran h5 check");
        root.attr("version", std::int64_t{1});
        root.attr("box", std::vector<double>{1.0, 2.0});
        root.attr("counts", std::vector<std::int64_t>{3, 4});
        root.attr("species", std::vector<std::string>{"A", "βeta"});
        Group g = root.group("results/run0");
        g.write("x", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3});
        g.write("i", std::vector<std::int64_t>{-1, 2});
        g.write("u", std::vector<std::uint64_t>{5, 6});
        g.write_scalar("t", 0.5);
        g.write_scalar("n", std::int64_t{12});
        g.write_string("label", "φ run");
        g.write_strings("names", {"a", "b"});
        g.attr("alpha", 0.9);
        g.attr_on("x", "units", std::string("m"));
        g.attr_on("x", "scale", 2.0);
    }
    File f = File::open_read(file);
    EXPECT_EQ(f.root().group("results/run0").read_string("label"), "φ run");
}

}  // namespace
