// The one main() of every Boost.Test executable (tests/CMakeLists.txt): the test files define no
// BOOST_TEST_MODULE, so that they can share one precompiled header; the module is named after the
// executable, as each file's own BOOST_TEST_MODULE named it before.
#include <boost/test/unit_test.hpp>

#include <filesystem>

namespace {

bool init_unit_test() {
  auto& master = boost::unit_test::framework::master_test_suite();
  if (master.argc > 0) master.p_name.value = std::filesystem::path(master.argv[0]).filename().string();
  return true;
}

}  // namespace

int main(int argc, char* argv[]) { return boost::unit_test::unit_test_main(&init_unit_test, argc, argv); }
