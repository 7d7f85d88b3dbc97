#include <boost/test/unit_test.hpp>

#include <string>

#include "../support/fixtures.hpp"
#include "pounding/excitation/record_reader.hpp"
#include "pounding/input_error.hpp"

namespace tt = boost::test_tools;
using namespace pounding::excitation;
using pounding::InputError;
using pounding::testing::TempDir;

namespace {

const std::string kOlderHeader =
    "PEER NGA STRONG MOTION DATABASE RECORD\nTest event\nACCELERATION TIME SERIES IN UNITS OF G\n"
    "NPTS=   5, DT=   .0100 SEC,\n";
const std::string kWest2Header =
    "PEER NGA-West2\nTest event\nACCELERATION TIME SERIES IN UNITS OF G\n"
    "     5    0.0100    NPTS, DT\n";

RecordReadOptions at2() { return {}; }

/// Runs the reader and returns the error text; fails the test if nothing was thrown.
std::string error_of(const std::filesystem::path& file, const RecordReadOptions& options) {
  try {
    read_record(file, options);
  } catch (const InputError& error) {
    return error.what();
  }
  BOOST_FAIL("no error for " << file);
  return {};
}

bool mentions(const std::string& text, std::initializer_list<std::string> parts) {
  for (const auto& part : parts) {
    if (text.find(part) == std::string::npos) return false;
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(ReadsOlderPeerHeader) {
  TempDir dir;
  const auto samples =
      read_record(dir.write("a.AT2", kOlderHeader + "  .1000E-01  -.2000E-01  .3E-1\n  .4D-02  -5.0E-03\n"), at2());
  BOOST_TEST(samples.accel == std::vector<double>({0.01, -0.02, 0.03, 0.004, -0.005}),
             tt::per_element() /* exact parse */);
  BOOST_TEST(samples.time_s[4] == 0.04, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(ReadsNgaWest2Header) {
  TempDir dir;
  const auto samples = read_record(dir.write("b.AT2", kWest2Header + "1 2 3 4 5\n"), at2());
  BOOST_TEST(samples.accel.size() == 5u);
  BOOST_TEST(samples.time_s[1] == 0.01, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(AcceptsCrlfAndMissingFinalNewline) {
  TempDir dir;
  std::string crlf = kOlderHeader + "1 2 3\n4 5";
  for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2)) {
    crlf.replace(at, 1, "\r\n");
  }
  const auto samples = read_record(dir.write("c.AT2", crlf), at2());
  BOOST_TEST(samples.accel == std::vector<double>({1, 2, 3, 4, 5}), tt::per_element());

  const auto columns =
      read_record(dir.write("c.txt", "# t a\r\n0 1\r\n0.5 2\r\n1.0 3"), {.format = RecordFormat::columns});
  BOOST_TEST(columns.time_s == std::vector<double>({0, 0.5, 1.0}), tt::per_element());
}

BOOST_AUTO_TEST_CASE(TextInANumberFieldNamesLineFieldAndText) {
  TempDir dir;
  const auto file = dir.write("d.AT2", kOlderHeader + "1 2 3\n4 abc\n");
  BOOST_TEST(mentions(error_of(file, at2()), {"d.AT2", "line 6, field 2", "'abc'", "not a number"}));
}

BOOST_AUTO_TEST_CASE(NptsDisagreeingWithTheValuesIsRefused) {
  TempDir dir;
  const auto file = dir.write("e.AT2", kOlderHeader + "1 2 3 4\n");
  BOOST_TEST(mentions(error_of(file, at2()), {"e.AT2", "line 4", "announces 5", "holds 4"}));
}

BOOST_AUTO_TEST_CASE(ADecimalCommaNamesItsLineNotTheHeader) {
  // "0,2" read as two values made the count disagree with NPTS, and the header was blamed.
  TempDir dir;
  const auto file = dir.write("c.AT2", kOlderHeader + "1 0,2 3\n4\n");
  BOOST_TEST(mentions(error_of(file, at2()), {"c.AT2", "line 5", "'1 0,2 3'", "comma"}));
}

BOOST_AUTO_TEST_CASE(NonPositiveTimeStepIsRefused) {
  TempDir dir;
  std::string header = kOlderHeader;
  header.replace(header.find(".0100"), 5, "0.000");
  BOOST_TEST(mentions(error_of(dir.write("f.AT2", header + "1 2 3 4 5\n"), at2()),
                      {"f.AT2", "'0.000'", "DT must be positive"}));
  BOOST_TEST(mentions(error_of(dir.write("g.txt", "1 2 3\n"), {.format = RecordFormat::single, .dt_s = -0.01}),
                      {"g.txt", "positive time step"}));
}

BOOST_AUTO_TEST_CASE(EmptyAndMissingFilesAreRefused) {
  TempDir dir;
  BOOST_TEST(mentions(error_of(dir.write("h.txt", ""), {.format = RecordFormat::columns}), {"h.txt", "no samples"}));
  BOOST_TEST(mentions(error_of(dir.write("h.AT2", ""), at2()), {"h.AT2", "header lines"}));
  BOOST_TEST(mentions(error_of(dir.path() / "absent.AT2", at2()), {"absent.AT2", "cannot open"}));
}

BOOST_AUTO_TEST_CASE(NanAndInfinityAreRefused) {
  TempDir dir;
  BOOST_TEST(mentions(error_of(dir.write("i.AT2", kOlderHeader + "1 2 nan 4 5\n"), at2()),
                      {"line 5, field 3", "'nan'", "not finite"}));
  BOOST_TEST(mentions(error_of(dir.write("j.txt", "0 1\n0.1 inf\n"), {.format = RecordFormat::columns}),
                      {"line 2, field 2", "'inf'", "not finite"}));
}

BOOST_AUTO_TEST_CASE(ColumnsNeedIncreasingTimesAndTheAskedColumn) {
  TempDir dir;
  BOOST_TEST(mentions(error_of(dir.write("k.txt", "0 1\n0.1 2\n0.1 3\n"), {.format = RecordFormat::columns}),
                      {"line 3, field 1", "'0.1'", "increase"}));
  BOOST_TEST(
      mentions(error_of(dir.write("l.txt", "0 1\n0.1 2\n"), {.format = RecordFormat::columns, .accel_column = 3}),
               {"line 1", "column 3"}));
}

BOOST_AUTO_TEST_CASE(ColumnsAndSingleSelectTheAskedComponent) {
  TempDir dir;
  const auto file = dir.write("m.txt", "% two components\n0.0 1 10\n0.1 2 20\n0.2 3 30\n");
  const auto columns = read_record(file, {.format = RecordFormat::columns, .accel_column = 3});
  BOOST_TEST(columns.accel == std::vector<double>({10, 20, 30}), tt::per_element());

  const auto single = read_record(dir.write("n.txt", "1 10\n2 20\n3 30"),
                                  {.format = RecordFormat::single, .accel_column = 2, .dt_s = 0.005});
  BOOST_TEST(single.accel == std::vector<double>({10, 20, 30}), tt::per_element());
  BOOST_TEST(single.time_s[2] == 0.01, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(SingleReadsEveryNumberInOrderSkippingComments) {
  TempDir dir;
  const auto samples = read_record(dir.write("o.txt", "#header\n1 2 3\n4\n#*** End Data ***\n"),
                                   {.format = RecordFormat::single, .dt_s = 0.02});
  BOOST_TEST(samples.accel == std::vector<double>({1, 2, 3, 4}), tt::per_element());
  BOOST_TEST(samples.time_s[3] == 0.06, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(ReadsTheShippedElCentroRecord) {
  const auto samples = read_record(POUNDING_EXAMPLES_DIR "/records/elcentro1940_ns_0.02s.AT2", at2());
  BOOST_TEST(samples.accel.size() == 1559u);
  BOOST_TEST(samples.accel[101] == -0.31882);  // the peak, at 2.02 s (PROVENANCE.md)
  BOOST_TEST(samples.time_s.back() == 31.16, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(HugeNptsIsRefusedBeforeAnyConversion) {
  // NPTS = 1e30 once overflowed the conversion to an integer (undefined behaviour).
  TempDir dir;
  std::string header = kOlderHeader;
  header.replace(header.find("5,"), 1, "1e30");
  BOOST_TEST(mentions(error_of(dir.write("huge.AT2", header + "1 2 3 4 5\n"), at2()),
                      {"huge.AT2", "line 4", "'1e30'", "limit of 10000000 samples"}));
}

BOOST_AUTO_TEST_CASE(OverlongHeaderLineIsRefusedBeforeTheRegex) {
  // Found by fuzzing: a 10 kB header line kept std::regex backtracking for over 10 s.
  TempDir dir;
  const std::string header = "PEER\nev\nG\nNPTS= 5, DT= .01 SEC" + std::string(5000, ' ') + "x\n";
  BOOST_TEST(mentions(error_of(dir.write("long.AT2", header + "1 2 3 4 5\n"), at2()),
                      {"long.AT2", "line 4", "at most 200 characters"}));
}
