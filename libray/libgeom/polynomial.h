// Real roots of polynomials of degree ≤ 4 (quadratic, cubic, quartic).
//
// Coefficients are given leading-first: a·x⁴ + b·x³ + c·x² + d·x + e. Leading coefficients
// that are exactly zero lower the degree. Every solver returns the number of DISTINCT real
// roots it wrote, in ascending order; a multiple root (double, triple) is reported once.
// An identically zero polynomial has no isolated roots and returns 0.
//
// Method (cubic and quartic): the roots of the derivative split the line into pieces on
// which the polynomial is monotonic, so each piece holds at most one root. A piece whose
// end values change sign is searched by Halley's method (Newton's with a curvature
// correction; cubic convergence) safeguarded with bisection; a critical point where |p| is
// within the rounding-error bound of Horner's rule is reported as a multiple root (this is
// how tangent rays find double roots). Nothing is assumed about the spacing of the roots,
// so nearly equal roots are separated as long as the polynomial's values can tell them
// apart.
//
// Tolerances:
//  * "p(x) is zero" means |p(x)| ≤ kZeroTolerance · Σ|c_i|·|x|^i, a few times the
//    rounding-error bound 2·n·u of Horner's rule for degree n ≤ 4 (u = 2⁻⁵³).
//  * Roots are refined until the bracket is narrower than 4 ulp of the root (relative
//    accuracy ~1e-15), or |p| falls within Horner's rounding-error bound
//    (2n + 1)·u·Σ|c_i|·|x|^i (where p's computed sign, and so any further refinement, is
//    noise), or 100 iterations (each halves the bracket at worst) have been spent.
#pragma once

namespace rs {

inline constexpr double kZeroTolerance = 32 * 2.220446049250313e-16;

// a·x² + b·x + c. A discriminant within rounding error of zero gives one (double) root.
int SolveQuadratic(double a, double b, double c, double roots[2]);
// a·x³ + b·x² + c·x + d.
int SolveCubic(double a, double b, double c, double d, double roots[3]);
// a·x⁴ + b·x³ + c·x² + d·x + e.
int SolveQuartic(double a, double b, double c, double d, double e, double roots[4]);

// The distinct real roots of the polynomial Σ coeffs[i]·x^i (ASCENDING powers,
// 0 ≤ degree ≤ 4) lying in the closed interval [lo, hi], ascending. Restricting the
// interval (e.g. to a ray segment) is cheaper and better conditioned than solving on the
// whole line. Returns the count.
int SolvePolynomialInInterval(const double* coeffs, int degree, double lo, double hi,
                              double* roots);

// The distinct real roots of Σ coeffs[i]·x^i (ascending powers, degree ≤ 4) in [lo, hi],
// produced one at a time in ascending order and computed only as far as they are asked
// for: a ray that wants the nearest root beyond some distance stops after it. Holds
// copies of the coefficients; no allocation.
class AscendingRoots {
  public:
    AscendingRoots(const double* coeffs, int degree, double lo, double hi);
    // The next larger root; false when there are no more.
    bool Next(double& root) { return Next(0, root); }

  private:
    // One polynomial of the derivative chain with its walk state. Left uninitialised on
    // construction (this runs once per ray and interval): the constructor writes c and
    // degree, and Start the rest, before Next reads anything.
    struct Level {
        double c[5];
        int degree;
        double hi;
        bool done;
        // Degree ≤ 2: the closed-form roots in [lo, hi] and the next one to hand out.
        double closed[2];
        int nClosed, iClosed;
        // Degree ≥ 3: the last break reached and p there (0 when within rounding error),
        // and whether that zero still has to be reported as a root.
        double x0, v0;
        bool pendingZero;
    };

    static void Start(Level& level, double lo, double hi);
    static double ZeroedValue(const Level& level, double x);
    bool Next(int level, double& root);

    static constexpr int kMaxLevels = 3;  // p, p′, p″: a quartic's chain ends at p″
    Level levels_[kMaxLevels];
    int nLevels_;
};

// False when Σ coeffs[i]·x^i (ascending powers, degree ≤ 4) provably keeps one strict sign on
// [lo, hi] by a margin far above rounding error (its Bernstein coefficients there all share
// that sign), so none of the solvers above would report a root there; true otherwise. A
// cheap rejection test: rays that miss a quartic surface mostly end here.
bool MayHaveRoot(const double* coeffs, int degree, double lo, double hi);

// Σ coeffs[i]·x^i by Horner's rule.
double EvaluatePolynomial(const double* coeffs, int degree, double x);

}  // namespace rs
