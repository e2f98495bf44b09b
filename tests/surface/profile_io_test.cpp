// Profile readers: delimited text (incl. a real Dektak export), X3P (round trips of
// every data type and storage, a real MountainsMap file), and refusal of bad input.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
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
  expect_refused("x[mm],z[um]\n0,1\n0.001,2\n0.002,oops\n", "expected only numbers");
  expect_refused(std::string_view("x[mm],z[um]\n0,1\0", 16), "NUL");
}

// n lines "x,z" of a 1 um grid starting at x = first (um).
std::string grid_lines(std::size_t n, std::size_t first = 0) {
  std::string s;
  for (std::size_t i = first; i < first + n; ++i)
    s += fmt::format("{},{}\n", i, 0.1 * static_cast<double>(i % 7));
  return s;
}

TEST(ProfileText, ABreakInsideTheDataIsRefusedNotDropped) {
  // An instrument message between two runs of data: the longer run used to be read
  // alone (5000 of 6000 points, exit 0). Header on line 1, data on lines 2-5001.
  expect_refused(
      "x[um],z[um]\n" + grid_lines(5000) + "ERROR: stylus lifted\n" + grid_lines(1000, 5000),
      "line 5002: not a number inside the data (\"ERROR: stylus lifted\")");
  // A repeated header in the middle: the first block used to be dropped.
  expect_refused("x[um],z[um]\n" + grid_lines(1000) + "x[um],z[um]\n" + grid_lines(5000, 1000),
                 "line 1002: not a number inside the data (\"x[um],z[um]\")");
  // An empty line between two blocks.
  expect_refused("x[um],z[um]\n" + grid_lines(10) + "\n" + grid_lines(10, 10),
                 "line 12: not a number inside the data (an empty line)");
  // A malformed data line with data after it.
  expect_refused("x[mm],z[um]\n0,1\n0.001,2\n0.002,oops\n0.003,2\n", "line 4: not a number");
}

TEST(ProfileText, PreamblesAndFootersInAnotherLayoutAreAccepted) {
  // Numbers with another column count above or below the data (a point count, a
  // single calibration value) and text footers are not data.
  const auto p = parse_profile_text(
      "Points\n2000\nScan\n\nx[um],z[um]\n" + grid_lines(2000) + "\nEnd of data\nRq,0.1 um\n",
      "ok.csv");
  EXPECT_EQ(p.z.size(), 2000u);
  EXPECT_EQ(p.dx, 1e-6);
  // The real export (vendor preamble with numbers inside text lines) and the shipped
  // examples read whole: RealDektakExport and ShippedExamplesReadWithThePrintedStep.
}

TEST(ProfileText, ShippedExamplesReadWithThePrintedStep) {
  const std::string ex = kData + "/../../examples/roughness/";
  for (const char* name : {"pzt_max", "pzt_min", "lc_max", "lc_min"}) {
    SCOPED_TRACE(name);
    const auto p = read_profile_text(ex + name + ".csv");
    EXPECT_EQ(p.z.size(), 4001u);
    // x printed as 0.0000, 0.0010, ... mm: the fit gives 1.0000000000000008e-06 m;
    // the step is reported as the printed decimal, 1 um exactly.
    EXPECT_EQ(p.dx, 1e-6);
    EXPECT_EQ(p.x0, 0.0);
    // So ls = 5 dx is accepted (it was refused as "below 5 sample spacings").
    EXPECT_NO_THROW((void)(GaussianFilter{.lc = 0.8e-3, .ls = 5e-6}.apply(p)));
  }
  // A step that is no short decimal keeps the fitted value (Dektak: 0.15624.. um).
  const auto d = read_profile_text(kData + "/dektak-1.csv");
  EXPECT_NE(d.dx, 0.15625 * um);
  // A cut-off truly below 5 sample spacings is still refused.
  const auto p = read_profile_text(ex + "pzt_min.csv");
  EXPECT_THROW((void)(GaussianFilter{.lc = 0.8e-3, .ls = 4.9e-6}.apply(p)), InvalidInput);
}

TEST(ProfileText, TwoColumnsInTheOrderTheHeaderNames) {
  const auto p = parse_profile_text("z[um],x[mm]\n5,0\n6,0.002\n7,0.004\n8,0.006\n", "zx.csv");
  EXPECT_EQ(p.dx, 2e-6);
  EXPECT_NEAR(p.z[3], 8 * um, 1e-20);
  const auto q = parse_profile_text("height (nm)\tposition (um)\n1\t0\n2\t1\n3\t2\n", "h.txt");
  EXPECT_EQ(q.dx, 1e-6);
  EXPECT_NEAR(q.z[2], 3e-9, 1e-24);
  // Unnamed columns: x first.
  const auto r = parse_profile_text("a[um],b[nm]\n0,5\n1,6\n2,7\n", "ab.csv");
  EXPECT_EQ(r.dx, 1e-6);
  expect_refused("x[um],x_2[um]\n0,1\n1,2\n2,3\n", "both columns");
}

TEST(ProfileText, NonUniformSpacingNamesTheLineWhereItBreaks) {
  // Spacing changes from 1 to 2 um after 1500 points (lines 2-1501): the first x off
  // the grid is on line 1503 (the step into it is 2 um). The least-squares grid of all
  // points used to put the error on line 2.
  std::string s = "x[um],z[um]\n";
  for (std::size_t i = 0; i < 3000; ++i)
    s += fmt::format("{},{}\n", i < 1500 ? i : 1500 + 2 * (i - 1500),
                     0.1 * static_cast<double>(i % 7));
  expect_refused(s, "line 1503: x is not uniformly spaced");
  // One missing sample: x = 1499 is followed by 1501 on line 1502.
  s = "x[um],z[um]\n";
  for (std::size_t i = 0; i < 3000; ++i) s += fmt::format("{},{}\n", i < 1500 ? i : i + 1, 0.0);
  expect_refused(s, "line 1502: x is not uniformly spaced");
  // A break among the first points: the step check against the median step.
  expect_refused("x[um],z[um]\n0,1\n1,2\n2,1\n3.7,2\n4,1\n5,1\n6,1\n7,1\n8,1\n9,1\n",
                 "line 5: x is not uniformly spaced: the step");
  // A slow drift of the spacing, no single step out of line: 0.02 % per point.
  s = "x[um],z[um]\n";
  double x = 0;
  for (std::size_t i = 0; i < 3000; ++i, x += 1.0 + 2e-4 * static_cast<double>(i))
    s += fmt::format("{:.6f},0\n", x);
  expect_refused(s, "x is not uniformly spaced");
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
        // The writer's quantisation bounds the error: float64 is exact; float32 rounds
        // to 2^-24 relative, and inline the shortest decimal that reads back as that
        // float adds up to another 2^-24; the integer types round to the nearest step
        // of the increment the writer chooses, (hi - lo) / (2 (full scale - 1)), so
        // within increment/2, plus the rounding of offset + increment x value (a few
        // 1e-16 of the heights' 1e-6 m scale).
        double lo = INFINITY, hi = -INFINITY;
        for (std::size_t k = 0; k < m.z.size(); ++k) {
          if (!m.valid[k]) continue;
          lo = std::min(lo, m.z[k]);
          hi = std::max(hi, m.z[k]);
        }
        const double full = type == X3pDataType::int16 ? 32767.0 : 2147483647.0;
        const double increment = (hi - lo) / (2.0 * (full - 1.0));
        auto tol = [&](double z) {
          switch (type) {
            case X3pDataType::float64:
              return 0.0;
            case X3pDataType::float32:
              return std::abs(z) * (inline_data ? 0x1p-23 : 0x1p-24);
            default:
              return 0.5 * increment + 1e-15 * std::max(std::abs(lo), std::abs(hi));
          }
        };
        for (std::size_t k = 0; k < m.z.size(); ++k) {
          if (!m.valid[k]) {
            EXPECT_FALSE(r.is_valid(k % m.nx, k / m.nx));
            continue;
          }
          ASSERT_TRUE(r.is_valid(k % m.nx, k / m.nx)) << k;
          ASSERT_NEAR(r.z[k], m.z[k], tol(m.z[k])) << k;
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

// X3P files built byte by byte by tests/data/x3p/make_fixtures.py (zipfile, struct,
// hashlib; not our writer), so that a mistake our writer and reader share cannot pass.
// The expected heights are z = CZ Offset + CZ Increment x value (ISO 5436-2), written
// out here as decimals; the reader's two roundings (product and sum) stay within
// 4e-16 of the larger term.
const std::string kFixtures = kData + "/x3p/";

TEST(X3pIndependentFixtures, ProfileInt16WithOffsetAndIncrement) {
  const auto m = read_x3p(kFixtures + "prf_int16_offset.x3p");
  ASSERT_EQ(m.nx, 7u);
  ASSERT_EQ(m.ny, 1u);
  EXPECT_EQ(m.dx, 0.5e-6);
  EXPECT_EQ(m.x0, 1e-3);
  EXPECT_EQ(m.invalid_count(), 0u);
  // Values -32768, -1, 0, 1, 1234, -1234, 32767 (little-endian int16), 1 nm steps
  // about 2.5 um. Read big-endian, 1234 would be -11772 (z = -9.272 um).
  const double want[] = {-30.268e-6, 2.499e-6, 2.5e-6, 2.501e-6, 3.734e-6, 1.266e-6, 35.267e-6};
  for (std::size_t k = 0; k < 7; ++k) EXPECT_NEAR(m.z[k], want[k], 4e-16 * 35e-6) << k;
}

TEST(X3pIndependentFixtures, ArealInt32WithInvalidPointMask) {
  const auto m = read_x3p(kFixtures + "sur_int32_mask.x3p");
  ASSERT_EQ(m.nx, 5u);
  ASSERT_EQ(m.ny, 3u);
  EXPECT_EQ(m.dx, 1e-6);
  EXPECT_EQ(m.dy, 2e-6);
  EXPECT_EQ(m.y0, 5e-6);
  // valid.bin = 3D EF: bit k % 8 of byte k / 8, least significant bit first, 1 = valid
  // (openGPS ISO5436_2_XML reference library, src/ISO5436_2_XML/cxx/valid_buffer.cxx,
  // ValidBuffer::IsValid; we could not consult the ISO 5436-2:2012 text itself). So
  // points 1, 6, 7 and 12 are invalid; most-significant-bit first would give 0, 1, 6
  // and 11.
  for (std::size_t k = 0; k < 15; ++k) {
    const bool invalid = k == 1 || k == 6 || k == 7 || k == 12;
    EXPECT_EQ(m.is_valid(k % 5, k / 5), !invalid) << k;
    if (invalid) {
      EXPECT_TRUE(std::isnan(m.z[k])) << k;
    } else {
      // Values 1000 k - 7000 in steps of 1e-10 m: z = (k - 7) 1e-7 m.
      EXPECT_NEAR(m.z[k], (static_cast<double>(k) - 7.0) * 1e-7, 4e-16 * 7e-7) << k;
    }
  }
  EXPECT_EQ(m.invalid_count(), 4u);
  // Row 1 (points 5-9) loses 6 and 7: its longest valid run is 8-9.
  EXPECT_EQ(m.rows()[1].z.size(), 2u);
}

TEST(X3pIndependentFixtures, InlineDataListWithAnEmptyDatum) {
  const auto m = read_x3p(kFixtures + "prf_datalist_empty.x3p");
  ASSERT_EQ(m.nx, 6u);
  EXPECT_EQ(m.dx, 2e-6);
  // Datum texts 1.5e-6, -2.25E-06, <Datum/>, " 3.0e-6 ", 4e-7, 0; type D, Increment 1,
  // Offset 0: the heights are the decimals themselves.
  EXPECT_EQ(m.z[0], 1.5e-6);
  EXPECT_EQ(m.z[1], -2.25e-6);
  EXPECT_FALSE(m.is_valid(2, 0));
  EXPECT_EQ(m.z[3], 3.0e-6);
  EXPECT_EQ(m.z[4], 4e-7);
  EXPECT_EQ(m.z[5], 0.0);
  EXPECT_EQ(m.invalid_count(), 1u);
  EXPECT_EQ(m.as_profile().z.size(), 3u);  // the longest valid run, points 3-5
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
    expect_x3p_refused(zip_x3p_package(pkg), "is not a size between 1 and 33554432");
    // Issue 13's decompression bomb: each axis within its cap, the product (2^28 points,
    // 2 GiB of doubles) past the stated limit of 2^25 points.
    pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeX>20</SizeX>", "<SizeX>16384</SizeX>");
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeY>10</SizeY>", "<SizeY>16384</SizeY>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg),
                       "SizeX x SizeY = 16384 x 16384 exceeds 33554432 points");
    pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeX>20</SizeX>", "<SizeX>2000</SizeX>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "need");
  }
  {  // the zip headers claim the size main.xml needs, the compressed stream holds less:
     // the real uncompressed size is checked (streamed, nothing kept) before allocating
    auto pkg = good;
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<SizeX>20</SizeX>", "<SizeX>2000</SizeX>");
    pkg.update_main_checksum();
    std::string bytes = zip_x3p_package(pkg);
    const std::uint32_t claimed = 2000u * 10u * 8u;  // float64 points
    const std::string name = "bindata/data.bin";
    auto patch = [&](std::string_view signature, std::size_t name_at, std::size_t size_at) {
      std::size_t found = 0;
      for (auto p = bytes.find(signature); p != std::string::npos;
           p = bytes.find(signature, p + 1)) {
        if (bytes.compare(p + name_at, name.size(), name) != 0) continue;
        for (int b = 0; b < 4; ++b)
          bytes[p + size_at + static_cast<std::size_t>(b)] = static_cast<char>(claimed >> (8 * b));
        ++found;
      }
      EXPECT_EQ(found, 1u) << signature;
    };
    patch(std::string_view("PK\x03\x04", 4), 30, 22);  // local header: size at 22, name at 30
    patch(std::string_view("PK\x01\x02", 4), 46, 24);  // central directory: 24, 46
    try {
      (void)parse_x3p(bytes, "bad.x3p");
      ADD_FAILURE() << "a zip entry shorter than its header was accepted";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.x3p: bindata/data.bin"), std::string::npos) << what;
      EXPECT_TRUE(what.find("1600 bytes, but 2000 x 10 points") != std::string::npos ||
                  what.find("corrupt") != std::string::npos)
          << what;
    }
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

// Replaces the text of the k-th (0-based) Datum of an inline package.
void set_datum(X3pPackage& pkg, std::size_t k, std::string_view text) {
  auto& xml = pkg.file("main.xml");
  std::size_t p = 0;
  for (std::size_t i = 0; i <= k; ++i) {
    p = xml.find("<Datum", p);
    ASSERT_NE(p, std::string::npos);
    if (i < k) ++p;
  }
  const auto gt = xml.find('>', p);
  const auto end = xml[gt - 1] == '/' ? gt + 1 : xml.find("</Datum>", gt) + 8;
  xml.replace(p, end - p, fmt::format("<Datum>{}</Datum>", text));
  pkg.update_main_checksum();
}

TEST(X3p, InlineValuesMustFitTheDataType) {
  const auto m = test_map(20, 1, false);
  for (auto [type, value, fragment] :
       {std::tuple{X3pDataType::int32, "1e300", "Datum 17 = \"1e300\" is not an integer"},
        std::tuple{X3pDataType::int32, "2147483648", "Datum 17 = 2147483648 is outside the range"},
        std::tuple{X3pDataType::int32, "12.5", "Datum 17 = \"12.5\" is not an integer"},
        std::tuple{X3pDataType::int16, "32768", "Datum 17 = 32768 is outside the range [-32768"},
        std::tuple{X3pDataType::int16, "-32769", "outside the range"},
        std::tuple{X3pDataType::int16, "abc", "is not an integer"},
        std::tuple{X3pDataType::float32, "1e300",
                   "not a finite number in the range of data type F"},
        std::tuple{X3pDataType::float64, "inf", "Datum 17 = \"inf\" is not a finite number"},
        std::tuple{X3pDataType::float64, "nan", "is not a finite number"},
        std::tuple{X3pDataType::float64, "1e999", "is not a finite number"},
        std::tuple{X3pDataType::float64, "0x10", "is not a number"},
        std::tuple{X3pDataType::float64, "1e-6;2e-6", "is not a number"}}) {
    SCOPED_TRACE(value);
    auto pkg = make_x3p_package(m, {.type = type, .inline_data = true});
    set_datum(pkg, 16, value);
    expect_x3p_refused(zip_x3p_package(pkg), fragment);
  }
  // In range: accepted (the extremes of int16).
  auto pkg = make_x3p_package(m, {.type = X3pDataType::int16, .inline_data = true});
  set_datum(pkg, 0, "-32768");
  set_datum(pkg, 1, "+32767");
  EXPECT_NO_THROW((void)parse_x3p(zip_x3p_package(pkg), "ok.x3p"));
  // A finite value that offset + increment x value turns into infinity.
  pkg = make_x3p_package(m, {.inline_data = true});
  set_datum(pkg, 3, "1e308");
  pkg.file("main.xml") =
      replace(pkg.file("main.xml"), "<DataType>D</DataType><Increment>1</Increment>",
              "<DataType>D</DataType><Increment>10</Increment>");
  pkg.update_main_checksum();
  expect_x3p_refused(zip_x3p_package(pkg), "Datum 4: CZ Offset + Increment x 1e+308 overflows");
  // Markup other than Datum inside the DataList.
  pkg = make_x3p_package(m, {.inline_data = true});
  pkg.file("main.xml") = replace(pkg.file("main.xml"), "<DataList>", "<DataList><Foo/>");
  pkg.update_main_checksum();
  expect_x3p_refused(zip_x3p_package(pkg), "an element other than Datum");
}

TEST(X3p, OversizedEntriesAreRefusedBeforeTheyAreRead) {
  const auto m = test_map(20, 10, false);
  {  // main.xml of 65 MiB (white space compresses 1000:1: a 65 KB file)
    auto pkg = make_x3p_package(m);
    pkg.file("main.xml") += std::string(65u << 20, ' ');
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg),
                       "main.xml: the archive says this entry holds 65 MiB uncompressed, more "
                       "than the 64 MiB allowed");
  }
  {  // 2 MiB of metadata outside the DataList (parsed into a DOM)
    auto pkg = make_x3p_package(m);
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "</Record2>", std::string(2u << 20, ' ') + "</Record2>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "MiB of XML outside Record3/DataList, more than");
  }
  {  // a DataList far longer than its points need
    auto pkg = make_x3p_package(test_map(5, 1, false), {.inline_data = true});
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<DataList>", "<DataList>" + std::string(1u << 20, '\n'));
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "more than 128 bytes a point");
  }
  {  // md5checksum.hex is 32 hex digits and a name, not 600 bytes
    auto pkg = make_x3p_package(m);
    pkg.file("md5checksum.hex") += std::string(600, ' ');
    expect_x3p_refused(zip_x3p_package(pkg), "md5checksum.hex: the archive says this entry holds");
  }
  {  // the checksum file named in Record4 pointing at the point data
    auto pkg = make_x3p_package(m);
    pkg.file("main.xml") =
        replace(pkg.file("main.xml"), "<ChecksumFile>md5checksum.hex</ChecksumFile>",
                "<ChecksumFile>bindata/data.bin</ChecksumFile>");
    pkg.update_main_checksum();
    expect_x3p_refused(zip_x3p_package(pkg), "bindata/data.bin: the archive says");
  }
}

TEST(X3p, FileWithoutValidPointsSaysSo) {
  // Written with every point invalid (NaN in float64 data, and a mask of zeros for an
  // integer type), read back: the file holds no valid points, whatever the filter.
  for (const bool masked : {false, true}) {
    auto m = test_map(9, 1, false);
    m.valid.assign(m.z.size(), 0);
    m.z[0] = 1e-6;  // one valid point, so that the writer has a range to scale
    m.valid[0] = 1;
    auto pkg = make_x3p_package(
        m, {.type = masked ? X3pDataType::int32 : X3pDataType::float64, .inline_data = false});
    if (masked) {
      // Clear the last valid bit too and fix the mask's checksum in main.xml.
      std::string& mask = pkg.file("bindata/valid.bin");
      const std::string old_md5 = detail::md5_hex(mask);
      mask.assign(mask.size(), '\0');
      pkg.file("main.xml") = replace(pkg.file("main.xml"), old_md5, detail::md5_hex(mask));
    } else {
      std::string& data = pkg.file("bindata/data.bin");
      const std::string old_md5 = detail::md5_hex(data);
      const std::string nan_bytes = pkg.file("bindata/data.bin").substr(8, 8);  // point 1: NaN
      data.replace(0, 8, nan_bytes);
      pkg.file("main.xml") = replace(pkg.file("main.xml"), old_md5, detail::md5_hex(data));
    }
    pkg.update_main_checksum();
    const auto read = parse_x3p(zip_x3p_package(pkg), "empty.x3p");
    EXPECT_EQ(read.invalid_count(), 9u);
    try {
      (void)read.as_profile();
      ADD_FAILURE() << "accepted a profile without valid points";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(
                    "empty.x3p: the file holds no valid points (all 9 are invalid)"),
                std::string::npos)
          << e.what();
    }
  }
}

// The file reader streams 1 MiB pieces through the same scanner parse_profile_text()
// runs over the whole text: a file whose CRLF pair, a number and a line straddle the
// piece boundary (byte 2^20) reads as the same profile, to the bit, as its text parsed
// at once; so do the same data with CR-only line ends and with a refused line.
TEST(ProfileText, FileReadInPiecesEqualsTheWholeText) {
  const auto dir =
      std::filesystem::temp_directory_path() /
      fmt::format("asperity_pieces_{}", ::testing::UnitTest::GetInstance()->random_seed());
  std::filesystem::create_directories(dir);
  for (const char* eol : {"\r\n", "\r"}) {
    for (std::size_t pad = 0; pad < 24; ++pad) {
      std::string text = "# " + std::string(pad, '-') + eol + "x[mm],z[um]" + eol;
      for (std::size_t i = 0; text.size() < (std::size_t{1} << 20) + 200; ++i) {
        text += fmt::format("{:.4f},{:.6f}{}", 1e-3 * static_cast<double>(i),
                            std::sin(0.01 * static_cast<double>(i)), eol);
      }
      const auto path = (dir / "p.csv").string();
      {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        ASSERT_NE(f, nullptr);
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
      }
      const Profile a = read_profile_text(path);
      const Profile b = parse_profile_text(text, path);
      ASSERT_EQ(a.z, b.z) << "pad " << pad;
      ASSERT_EQ(a.dx, b.dx);
      ASSERT_EQ(a.x0, b.x0);
      if (pad == 0) {
        // A broken line near the end: the same message (with its line number) either way.
        const std::string broken = text + "1.0,abc" + eol;
        const auto bad = (dir / "bad.csv").string();
        std::FILE* f = std::fopen(bad.c_str(), "wb");
        ASSERT_NE(f, nullptr);
        std::fwrite(broken.data(), 1, broken.size(), f);
        std::fclose(f);
        std::string from_file, from_text;
        try {
          (void)read_profile_text(bad);
        } catch (const InvalidInput& e) {
          from_file = e.what();
        }
        try {
          (void)parse_profile_text(broken, bad);
        } catch (const InvalidInput& e) {
          from_text = e.what();
        }
        EXPECT_NE(from_file.find("expected only numbers"), std::string::npos) << from_file;
        EXPECT_EQ(from_file, from_text);
      }
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace asperity::surface
