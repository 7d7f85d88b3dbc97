// The vectors the integrators use (sv::make_vector) carry element-wise kernels compiled in
// this project instead of the SUNDIALS library's. They must give bit for bit what the library's
// serial vector gives, in every special case its N_VLinearSum and N_VScale take (a, b = ±1, a = ±b,
// the result written over an operand), so that the integrators' steps do not change.

#include <boost/test/unit_test.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "pounding/solvers/sundials_handles.hpp"

namespace sv = pounding::solvers::sundials;  // SUNDIALS has its own ::sundials

namespace {

constexpr long kLength = 37;  // odd, so no kernel can assume pairs of elements

/// A compiled vector and a library vector holding the same values.
struct Pair {
  sv::Vector compiled;
  sv::Vector library;
};

class Fixture {
 public:
  Fixture() : context_(sv::make_context()) {}

  Pair pair(double low, double high) {
    Pair p{sv::make_vector(kLength, context_.get()), sv::Vector(N_VNew_Serial(kLength, context_.get()))};
    std::uniform_real_distribution<double> value(low, high);
    for (long i = 0; i < kLength; ++i) {
      NV_Ith_S(p.compiled.get(), i) = NV_Ith_S(p.library.get(), i) = value(random_);
    }
    return p;
  }

 private:
  sv::Context context_;
  std::mt19937_64 random_{12};
};

bool same_bits(N_Vector a, N_Vector b) {
  return std::memcmp(N_VGetArrayPointer(a), N_VGetArrayPointer(b), kLength * sizeof(double)) == 0;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

const std::vector<double> kCoefficients{1.0, -1.0, 0.0, 2.5, -2.5, 0.3, -0.7};

}  // namespace

BOOST_FIXTURE_TEST_CASE(LinearSumMatchesTheLibraryInEveryCaseAndAliasing, Fixture) {
  for (double a : kCoefficients) {
    for (double b : kCoefficients) {
      for (int alias = 0; alias < 3; ++alias) {  // z apart, z = x, z = y
        Pair x = pair(-3.0, 3.0), y = pair(-1e-3, 1e-3), z = pair(0.0, 1.0);
        N_Vector zc = alias == 1 ? x.compiled.get() : alias == 2 ? y.compiled.get() : z.compiled.get();
        N_Vector zl = alias == 1 ? x.library.get() : alias == 2 ? y.library.get() : z.library.get();
        N_VLinearSum(a, x.compiled.get(), b, y.compiled.get(), zc);
        N_VLinearSum(a, x.library.get(), b, y.library.get(), zl);
        BOOST_TEST(same_bits(zc, zl), "a = " << a << ", b = " << b << ", alias " << alias);
      }
    }
  }
}

BOOST_FIXTURE_TEST_CASE(ScaleAndElementwiseOperationsMatchTheLibrary, Fixture) {
  for (double c : kCoefficients) {
    Pair x = pair(-2.0, 2.0), z = pair(0.0, 1.0);
    N_VScale(c, x.compiled.get(), z.compiled.get());
    N_VScale(c, x.library.get(), z.library.get());
    BOOST_TEST(same_bits(z.compiled.get(), z.library.get()), "scale by " << c);
    N_VScale(c, x.compiled.get(), x.compiled.get());
    N_VScale(c, x.library.get(), x.library.get());
    BOOST_TEST(same_bits(x.compiled.get(), x.library.get()), "scale in place by " << c);
  }
  Pair x = pair(0.5, 2.0), y = pair(-4.0, 4.0), z = pair(0.0, 1.0);
  auto check = [&](const char* what) { BOOST_TEST(same_bits(z.compiled.get(), z.library.get()), what); };
  N_VProd(x.compiled.get(), y.compiled.get(), z.compiled.get());
  N_VProd(x.library.get(), y.library.get(), z.library.get());
  check("prod");
  N_VDiv(y.compiled.get(), x.compiled.get(), z.compiled.get());
  N_VDiv(y.library.get(), x.library.get(), z.library.get());
  check("div");
  N_VAbs(y.compiled.get(), z.compiled.get());
  N_VAbs(y.library.get(), z.library.get());
  check("abs");
  N_VInv(y.compiled.get(), z.compiled.get());
  N_VInv(y.library.get(), z.library.get());
  check("inv");
  N_VAddConst(y.compiled.get(), 0.1, z.compiled.get());
  N_VAddConst(y.library.get(), 0.1, z.library.get());
  check("addconst");
  N_VConst(-0.25, z.compiled.get());
  N_VConst(-0.25, z.library.get());
  check("const");
  N_VCompare(1.0, y.compiled.get(), z.compiled.get());
  N_VCompare(1.0, y.library.get(), z.library.get());
  check("compare");
  NV_Ith_S(y.compiled.get(), 5) = NV_Ith_S(y.library.get(), 5) = 0.0;  // InvTest skips and reports zeros
  BOOST_TEST(N_VInvTest(y.compiled.get(), z.compiled.get()) == N_VInvTest(y.library.get(), z.library.get()));
  check("invtest");
}

BOOST_FIXTURE_TEST_CASE(NormsAndReductionsMatchTheLibrary, Fixture) {
  Pair x = pair(-1e-4, 1e-4), w = pair(1e6, 1e9), id = pair(-1.0, 1.0);
  BOOST_TEST(same_bits(N_VWrmsNorm(x.compiled.get(), w.compiled.get()), N_VWrmsNorm(x.library.get(), w.library.get())));
  BOOST_TEST(same_bits(N_VWrmsNormMask(x.compiled.get(), w.compiled.get(), id.compiled.get()),
                       N_VWrmsNormMask(x.library.get(), w.library.get(), id.library.get())));
  BOOST_TEST(same_bits(N_VDotProd(x.compiled.get(), w.compiled.get()), N_VDotProd(x.library.get(), w.library.get())));
  BOOST_TEST(same_bits(N_VMaxNorm(x.compiled.get()), N_VMaxNorm(x.library.get())));
  BOOST_TEST(same_bits(N_VMin(x.compiled.get()), N_VMin(x.library.get())));
  N_VConst(0.0, x.compiled.get());
  N_VConst(0.0, x.library.get());
  BOOST_TEST(N_VWrmsNorm(x.compiled.get(), w.compiled.get()) == 0.0);
}

BOOST_FIXTURE_TEST_CASE(ClonesCarryTheCompiledOperations, Fixture) {
  // CVODE and ARKODE make their work vectors as clones of the state vector handed to them.
  Pair x = pair(-1.0, 1.0);
  const sv::Vector clone(N_VClone(x.compiled.get()));
  BOOST_TEST((clone->ops->nvlinearsum == x.compiled->ops->nvlinearsum));
  BOOST_TEST((clone->ops->nvwrmsnorm == x.compiled->ops->nvwrmsnorm));
  BOOST_TEST((clone->ops->nvlinearsum != x.library->ops->nvlinearsum));
  // The fused combination SUNDIALS composes from them (X[0] = z, as CVODE's predictor uses it).
  Pair y = pair(-1.0, 1.0), v = pair(-1.0, 1.0);
  double c[3] = {0.5, -1.0, 3.0};
  N_Vector compiled[3] = {x.compiled.get(), y.compiled.get(), v.compiled.get()};
  N_Vector library[3] = {x.library.get(), y.library.get(), v.library.get()};
  BOOST_TEST(N_VLinearCombination(3, c, compiled, x.compiled.get()) == 0);
  BOOST_TEST(N_VLinearCombination(3, c, library, x.library.get()) == 0);
  BOOST_TEST(same_bits(x.compiled.get(), x.library.get()));
}
