// Profile readers: delimited text (incl. a real Dektak export), X3P (round trips of
// every data type and storage, a real MountainsMap file), and refusal of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "../../src/surface/detail/md5.hpp"
#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::surface {
namespace {

constexpr double um = 1e-6;
const std::string kData = ASPERITY_TEST_DATA_DIR;

// ------------------------------------------------------------------ MD5

TEST(ProfileMd5, Rfc1321Vectors) {
  EXPECT_EQ(detail::md5_hex(""), "d41d8cd98f00b204e9800998ecf8427e");
  EXPECT_EQ(detail::md5_hex("abc"), "900150983cd24fb0d6963f7d28e17f72");
  EXPECT_EQ(detail::md5_hex("message digest"), "f96b697d7cb7938d525a2f31aaf161d0");
  EXPECT_EQ(detail::md5_hex(
                "12345678901234567890123456789012345678901234567890123456789012345678901234567890"),
            "57edf4a22be3c955ac49da2e2107b67a");
}

// ------------------------------------------------------------------ text

TEST(ProfileText, RealDektakExport) {
  const auto p = read_profile_text(kData + "/dektak-1.csv");
  // 1500 um at 0.156 um/sample (the export prints x to 0.1 um): 9600 points at
  // 1500/9600 = 0.15625 um.
  EXPECT_NEAR(p.length(), 1499.84 * um, 0.01 * um);
  EXPECT_NEAR(p.dx, 0.15625 * um, 0.0001 * um);
  EXPECT_NEAR(p.x0, 0.0, 0.05 * um);
  EXPECT_EQ(p.z.size(), 9600u);
  EXPECT_NEAR(p.z.front(), -0.00933 * um, 1e-15);
  EXPECT_NEAR(p.z.back(), 16.58112 * um, 1e-15);
  // A strong tilt: line levelling removes it.
  const auto l = level(p, Levelling::line);
  double rms = 0, rms_raw = 0;
  for (std::size_t i = 0; i < p.z.size(); ++i) {
    rms += l.z[i] * l.z[i];
    rms_raw += p.z[i] * p.z[i];
  }
  EXPECT_LT(std::sqrt(rms), 0.2 * std::sqrt(rms_raw));
}

TEST(ProfileText, HeaderUnitForms) {
  const auto a = parse_profile_text("x[mm],z[um]\n0,1\n0.001,2\n0.002,3\n", "a.csv");
  EXPECT_NEAR(a.dx, 1 * um, 1e-15);
  EXPECT_NEAR(a.z[2], 3 * um, 1e-18);
  const auto b = parse_profile_text("x_um;z_nm\r\n0;10\r\n0.5;20\r\n1.0;30\r\n", "b.csv");
  EXPECT_NEAR(b.dx, 0.5 * um, 1e-15);
  EXPECT_NEAR(b.z[0], 10e-9, 1e-20);
  const auto c =
      parse_profile_text("# scan\nx (mm)\tz (\xB5m)\n0\t1\n0.01\t2\n", "c.txt");  // Latin-1 µ
  EXPECT_NEAR(c.z[1], 2 * um, 1e-18);
  const auto d =
      parse_profile_text("\xEF\xBB\xBFx[\xC2\xB5m] z[\xC2\xB5m]\n0 1\n1 2\n2 3\n", "d.txt");
  EXPECT_NEAR(d.dx, 1 * um, 1e-15);
  const auto e = parse_profile_text("z[um]\n1\n2\n3\n4\n", "e.csv", {.dx = 0.5 * um});
  EXPECT_EQ(e.z.size(), 4u);
  EXPECT_NEAR(e.dx, 0.5 * um, 1e-18);
  const auto f = parse_profile_text(
      "Lateral um,Raw Micrometer,\n0.0,1,,\n0.2,2,,\n0.3,3,,\n0.5,4,,\n", "f.csv");
  EXPECT_NEAR(f.dx, 0.16 * um, 1e-15);  // least-squares grid through 0, 0.2, 0.3, 0.5
}

void expect_refused(std::string_view content, std::string_view fragment,
                    const TextReadOptions& o = {}) {
  try {
    (void)parse_profile_text(content, "bad.csv", o);
    ADD_FAILURE() << "accepted: " << content;
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.csv"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(ProfileText, BadInputIsRefusedWithClearMessages) {
  expect_refused("", "no data");
  expect_refused("x[mm],z[um]\n", "no data");
  expect_refused("x[mm],z[um]\n0,1\n", "at least 2");
  expect_refused("x[mm],z[um]\n0,1\n0.002,2\n0.001,3\n", "does not increase");
  expect_refused("x[mm],z[um]\n0,1\n0.001,2\n0.002,2\n0.005,3\n0.006,3\n", "not uniformly spaced");
  expect_refused("x[mm],z[um]\n0,1\n0.001,nan\n0.002,2\n", "not a finite number");
  expect_refused("x[mm],z[furlong]\n0,1\n0.001,2\n", "no known length unit");
  expect_refused("x,z\n0,1\n0.001,2\n", "no known length unit");
  expect_refused("0,1\n0.001,2\n", "no header");
  expect_refused("z[um]\n1\n2\n", "--dx");
  expect_refused("a,b,c\n1,2,3\n4,5,6\n", "3 columns");
  expect_refused("x[mm],z[um]\n0,1\n0.001,2\n0.002,oops\n0.003,2\n", "expected only numbers");
  expect_refused(std::string_view("x[mm],z[um]\n0,1\0", 16), "NUL");
}

// ------------------------------------------------------------------ X3P

HeightMap test_map(std::size_t nx, std::size_t ny, bool holes) {
  HeightMap m;
  m.nx = nx;
  m.ny = ny;
  m.dx = 0.5 * um;
  m.dy = ny > 1 ? 0.75 * um : 0.0;
  m.x0 = 1e-5;
  m.source = "test map";
  m.z.resize(nx * ny);
  for (std::size_t k = 0; k < m.z.size(); ++k) {
    m.z[k] = 1e-6 * std::sin(0.1 * static_cast<double>(k)) + 1e-8 * static_cast<double>(k % 7);
  }
  if (holes) {
    m.valid.assign(m.z.size(), 1);
    for (std::size_t k = 3; k < m.z.size(); k += 11) {
      m.valid[k] = 0;
      m.z[k] = std::nan("");
    }
  }
  return m;
}

TEST(X3p, RoundTripEveryTypeAndStorage) {
  for (bool sur : {false, true}) {
    for (bool inline_data : {false, true}) {
      for (auto type :
           {X3pDataType::int16, X3pDataType::int32, X3pDataType::float32, X3pDataType::float64}) {
        SCOPED_TRACE(::testing::Message() << "sur " << sur << " inline " << inline_data << " type "
                                          << static_cast<int>(type));
        const auto m = test_map(37, sur ? 13 : 1, true);
        const auto bytes =
            zip_x3p_package(make_x3p_package(m, {.type = type, .inline_data = inline_data}));
        const auto r = parse_x3p(bytes, "round trip");
        ASSERT_EQ(r.nx, m.nx);
        ASSERT_EQ(r.ny, m.ny);
        EXPECT_DOUBLE_EQ(r.dx, m.dx);
        if (sur) {
          EXPECT_DOUBLE_EQ(r.dy, m.dy);
        }
        EXPECT_DOUBLE_EQ(r.x0, m.x0);
        EXPECT_EQ(r.invalid_count(), m.invalid_count());
        const double tol = type == X3pDataType::float64   ? 0.0
                           : type == X3pDataType::float32 ? 1e-13
                           : type == X3pDataType::int32   ? 1e-15
                                                          : 1e-10;
        for (std::size_t k = 0; k < m.z.size(); ++k) {
          if (!m.valid[k]) {
            EXPECT_FALSE(r.is_valid(k % m.nx, k / m.nx));
            continue;
          }
          ASSERT_TRUE(r.is_valid(k % m.nx, k / m.nx)) << k;
          ASSERT_NEAR(r.z[k], m.z[k], tol) << k;
        }
      }
    }
  }
}

TEST(X3p, WriteAndReadFile) {
  const auto path = (std::filesystem::temp_directory_path() / "asperity-x3p-test.x3p").string();
  const auto m = test_map(50, 1, false);
  write_x3p(path, m);
  const auto r = read_height_file(path);
  EXPECT_TRUE(r.is_profile());
  EXPECT_EQ(r.z, m.z);
  const auto p = r.as_profile();
  EXPECT_EQ(p.z.size(), 50u);
  std::filesystem::remove(path);
}

TEST(X3p, RealMountainsMapFile) {
  const auto m = read_x3p(kData + "/mountainsmap-650x650.x3p");
  EXPECT_EQ(m.nx, 650u);
  EXPECT_EQ(m.ny, 650u);
  EXPECT_DOUBLE_EQ(m.dx, 1.27656509837346e-07);
  EXPECT_DOUBLE_EQ(m.dy, 3.14582113527746e-07);
  EXPECT_EQ(m.invalid_count(), 0u);
  EXPECT_DOUBLE_EQ(m.z[0], 6.579781341223288e-08);
  EXPECT_DOUBLE_EQ(m.z[1], 7.419121341223288e-08);    // x fastest
  EXPECT_DOUBLE_EQ(m.z[650], 6.233641341223288e-08);  // next row
  // Sq about the least-squares plane, as numpy computes it from the raw data.
  EXPECT_NEAR(m.rms_height_about_plane(), 7.719303278901976e-08, 1e-12);
  EXPECT_EQ(m.rows().size(), 650u);
  EXPECT_EQ(m.columns().size(), 650u);
}

void expect_x3p_refused(const std::string& bytes, std::string_view fragment) {
  try {
    (void)parse_x3p(bytes, "bad.x3p");
    ADD_FAILURE() << "accepted, expected: " << fragment;
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.x3p"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

std::string replace(std::string s, std::string_view from, std::string_view to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

TEST(X3p, BadInputIsRefusedWithClearMessages) {
  const auto m = test_map(20, 10, false);
  const auto good = make_x3p_package(m);
  expect_x3p_refused("", "zip");
  expect_x3p_refused("not a zip file at all", "zip");
  {
    const auto bytes = zip_x3p_package(good);
    expect_x3p_refused(bytes.substr(0, bytes.size() / 2), "zip");
  }
  {  // data changed: point-data checksum
    auto pkg = good;
    pkg.file("bindata/data.bin")[5] ^= 0x40;
    expect_x3p_refused(zip_x3p_package(pkg), "MD5 checksum mismatch");
  }
  {  // main.xml changed without updating md5checksum.hex
    auto pkg = good;
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "written by asperity", "edited");
    expect_x3p_refused(zip_x3p_package(pkg), "MD5 checksum mismatch");
  }
  {  // absurd size claimed in the header: refused before allocation
    auto pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeX>20</SizeX>", "<SizeX>100000000</SizeX>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "exceeds");
    pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeX>20</SizeX>", "<SizeX>2000</SizeX>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "need");
  }
  {  // missing entries
    auto pkg = good;
    pkg.files.erase(pkg.files.begin() + 1);  // bindata/data.bin
    expect_x3p_refused(zip_x3p_package(pkg), "missing from the archive");
    pkg = good;
    pkg.files.erase(pkg.files.begin());  // main.xml
    expect_x3p_refused(zip_x3p_package(pkg), "main.xml: missing");
    pkg = good;
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "<FeatureType>SUR</FeatureType>", "");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "FeatureType is missing");
  }
  {  // unsupported or malformed content
    auto pkg = good;
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "<FeatureType>SUR", "<FeatureType>PCL");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "PCL");
    pkg = good;
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "<SizeZ>1</SizeZ>", "<SizeZ>2</SizeZ>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "SizeZ");
    pkg = good;
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "</Record1>", "</Record>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "not well-formed");
    pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<DataType>D</DataType><Incr", "<DataType>Q</DataType><Incr");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "expected I, L, F or D");
  }
  {  // inline data with the wrong count
    auto pkg = make_x3p_package(test_map(5, 1, false), {.inline_data = true});
    pkg.file("main.xml") = replace(pkg.file("main.xml"), "<Datum>", "<Datum>1</Datum><Datum>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "Datum elements");
  }
}

}  // namespace
}  // namespace asperity::surface
