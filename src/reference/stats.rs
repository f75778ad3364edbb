//! The few statistics needed to compare an estimate with an exact answer:
//! normal and Student-t quantiles and the Šidák correction. Used by the
//! tests, and by the `check` command, to turn a Monte Carlo standard error
//! into a tolerance that fixes the false-failure rate however many points
//! are compared.

use super::monte_carlo::{Estimate, REPLICATES};
use std::f64::consts::{PI, SQRT_2};

/// How far a Monte Carlo [`Estimate`] made with `samples` samples may lie
/// from the true `V` at the two-sided quantile `q` (from
/// [`student_t_two_sided_quantile`] with `REPLICATES − 1` degrees of
/// freedom): `q · stderr`, or, when the standard error is zero, the
/// resolution of one replicate, `1/m` with `m = ⌈samples / K⌉` its points.
///
/// A zero standard error means every replicate counted the same number of
/// unoccluded samples. Stratified counts are nearly deterministic (in 1D,
/// for a segment light, the count in an interval takes at most two
/// values), so all `K` replicates often agree while the truth lies between
/// two counts: the estimate then resolves `V` only to one count, `1/m`.
#[must_use]
pub fn agreement_tolerance(estimate: &Estimate, samples: u32, q: f64) -> f64 {
    if estimate.stderr > 0.0 {
        q * estimate.stderr
    } else {
        let k = REPLICATES.min(samples.max(1));
        1.0 / f64::from(samples.max(1).div_ceil(k))
    }
}

/// The outcome of [`agree`]: how many estimates were checked, at what
/// per-check quantile, and every one outside its tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct Agreement {
    /// How many estimates were compared.
    pub checked: usize,
    /// The two-sided Student-t quantile each check used (the Šidák-corrected
    /// level of the family-wise rate, `REPLICATES − 1` degrees of freedom).
    pub quantile: f64,
    /// The checks that failed, in index order.
    pub failures: Vec<Disagreement>,
}

impl Agreement {
    /// Whether every estimate agreed with its exact value.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

/// One estimate outside its tolerance ([`Agreement::failures`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disagreement {
    /// The estimate's index.
    pub index: usize,
    /// The estimate.
    pub estimate: Estimate,
    /// The exact value it was compared with.
    pub exact: f64,
    /// The tolerance it missed ([`agreement_tolerance`]).
    pub allowed: f64,
}

/// Why [`agree`] could not check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AgreeError {
    /// The estimates and the exact values differ in number.
    LengthMismatch {
        /// How many estimates.
        estimates: usize,
        /// How many exact values.
        exact: usize,
    },
    /// The family-wise rate is not in `(0, 1)`.
    Rate(f64),
    /// An exact value is not finite.
    NonFiniteExact(usize),
}

impl_error!(AgreeError, |error, f| match *error {
    AgreeError::LengthMismatch { estimates, exact } => {
        write!(f, "{estimates} estimates but {exact} exact values")
    }
    AgreeError::Rate(a) => {
        write!(
            f,
            "the family-wise false-failure rate must lie in (0, 1), got {a}"
        )
    }
    AgreeError::NonFiniteExact(i) => write!(f, "exact value {i} is not finite"),
});

/// Whether Monte Carlo estimates made with `samples` samples each agree with
/// exact values, at the family-wise false-failure rate `rate` over all of
/// them: each check is `|estimate − exact| ≤ agreement_tolerance` at the
/// Student-t quantile of the Šidák-corrected level `sidak(rate, n)` — so
/// when the exact values are right, all `n` checks pass with probability
/// at least `1 − rate`. One call for what a test of a method or a GPU port
/// against Monte Carlo needs.
///
/// # Errors
/// [`AgreeError`] when the lengths differ, `rate ∉ (0, 1)` or an exact
/// value is not finite.
pub fn agree(
    estimates: &[Estimate],
    exact: &[f64],
    samples: u32,
    rate: f64,
) -> Result<Agreement, AgreeError> {
    if estimates.len() != exact.len() {
        return Err(AgreeError::LengthMismatch {
            estimates: estimates.len(),
            exact: exact.len(),
        });
    }
    if !(rate > 0.0 && rate < 1.0) {
        return Err(AgreeError::Rate(rate));
    }
    if let Some(i) = exact.iter().position(|v| !v.is_finite()) {
        return Err(AgreeError::NonFiniteExact(i));
    }
    let quantile = student_t_two_sided_quantile(sidak(rate, estimates.len()), REPLICATES - 1);
    let failures = estimates
        .iter()
        .zip(exact)
        .enumerate()
        .filter_map(|(index, (&estimate, &exact))| {
            let allowed = agreement_tolerance(&estimate, samples, quantile);
            // A NaN estimate or tolerance fails.
            let within = (estimate.visibility - exact).abs() <= allowed;
            (!within).then_some(Disagreement {
                index,
                estimate,
                exact,
                allowed,
            })
        })
        .collect();
    Ok(Agreement {
        checked: estimates.len(),
        quantile,
        failures,
    })
}

/// The complementary error function `erfc(x) = 1 − erf(x)`, to about
/// `1e-15` relative for `x ≥ 0` (Maclaurin series of `erf` below 2, Lentz's
/// continued fraction above); `erfc(−x) = 2 − erfc(x)`. NaN gives NaN.
#[must_use]
pub fn erfc(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    if x < 0.0 {
        return 2.0 - erfc(-x);
    }
    if x < 2.0 {
        // erf(x) = 2/√π Σ (−1)ⁿ x^(2n+1) / (n! (2n+1)).
        let (mut term, mut sum, mut n) = (x, x, 0.0);
        loop {
            n += 1.0;
            term *= -x * x / n;
            let add = term / (2.0 * n + 1.0);
            sum += add;
            if add.abs() <= 1e-18 * sum.abs() {
                break;
            }
        }
        return 1.0 - sum * 2.0 / PI.sqrt();
    }
    // erfc(x) = e^(−x²)/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …)))).
    const TINY: f64 = 1e-300;
    let (mut f, mut c, mut d) = (x, x, 0.0_f64);
    for k in 1..500 {
        let a = f64::from(k) / 2.0;
        d = x + a * d;
        d = if d.abs() < TINY { TINY } else { d };
        c = x + a / c;
        c = if c.abs() < TINY { TINY } else { c };
        d = 1.0 / d;
        let delta = c * d;
        f *= delta;
        if (delta - 1.0).abs() < 1e-16 {
            break;
        }
    }
    (-x * x).exp() / PI.sqrt() / f
}

/// The two-sided standard normal quantile: the `z` with
/// `P(|Z| > z) = alpha`, for `alpha ∈ (0, 1)` (bisection on [`erfc`], to
/// the bisection's `1e-13`); `0` for `alpha ≥ 1`, `∞`-like `40` for
/// `alpha ≤ 0` or NaN.
#[must_use]
pub fn normal_two_sided_quantile(alpha: f64) -> f64 {
    bisect(40.0, |z| erfc(z / SQRT_2) > alpha)
}

/// `P(|T| < t)` for Student's `t` with `nu ≥ 1` degrees of freedom, by the
/// finite sums of Abramowitz and Stegun 26.7.3–4.
#[must_use]
pub fn student_t_coverage(t: f64, nu: u32) -> f64 {
    let nu = nu.max(1);
    let theta = (t.abs() / f64::from(nu).sqrt()).atan();
    let (s, c) = theta.sin_cos();
    if nu % 2 == 1 {
        // (2/π)(θ + sin θ (cos θ + (2/3) cos³θ + … )), the sum empty for ν = 1.
        let (mut sum, mut term) = (0.0, c);
        if nu > 1 {
            sum = c;
            for k in 1..=(nu - 3) / 2 {
                term *= c * c * f64::from(2 * k) / f64::from(2 * k + 1);
                sum += term;
            }
        }
        2.0 / PI * (theta + s * sum)
    } else {
        let (mut sum, mut term) = (1.0, 1.0);
        for k in 1..=(nu - 2) / 2 {
            term *= c * c * f64::from(2 * k - 1) / f64::from(2 * k);
            sum += term;
        }
        s * sum
    }
}

/// The two-sided Student-t quantile: the `q` with `P(|T| < q) = 1 − alpha`
/// for `nu` degrees of freedom (bisection on [`student_t_coverage`]). The
/// tolerance for an estimate whose standard error was itself estimated from
/// `nu + 1` replicates.
#[must_use]
pub fn student_t_two_sided_quantile(alpha: f64, nu: u32) -> f64 {
    bisect(1e6, |t| student_t_coverage(t, nu) < 1.0 - alpha)
}

/// Šidák's correction: the per-check level that keeps the family-wise
/// false-failure rate at `alpha` over `checks` independent checks,
/// `1 − (1 − alpha)^(1/checks)` (computed without cancellation).
#[must_use]
pub fn sidak(alpha: f64, checks: usize) -> f64 {
    -((-alpha).ln_1p() / checks.max(1) as f64).exp_m1()
}

/// The boundary in `[0, hi]` where `below` turns false (it is true below
/// the boundary and false above it).
fn bisect(hi: f64, below: impl Fn(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, hi);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_published_tables() {
        // Tables: z(0.05) = 1.959964, z(0.001) = 3.290527;
        // t(0.05, 15) = 2.131450, t(0.01, 1) = 63.65674, t(0.05, 2) = 4.302653.
        assert!((normal_two_sided_quantile(0.05) - 1.959_964).abs() < 1e-6);
        assert!((normal_two_sided_quantile(0.001) - 3.290_527).abs() < 1e-6);
        assert!((student_t_two_sided_quantile(0.05, 15) - 2.131_450).abs() < 1e-6);
        assert!((student_t_two_sided_quantile(0.01, 1) - 63.656_74).abs() < 1e-4);
        assert!((student_t_two_sided_quantile(0.05, 2) - 4.302_653).abs() < 1e-6);
        // Šidák over one check is the level itself; over k it multiplies
        // back: (1 − a_k)^k = 1 − a.
        assert!((sidak(0.01, 1) - 0.01).abs() < 1e-17);
        assert!(((1.0 - sidak(0.01, 1000)).powi(1000) - 0.99).abs() < 1e-12);
        // Closed forms: t₁ is Cauchy (P(|T| < 1) = 1/2); for t₂,
        // P(|T| < t) = t/√(2 + t²).
        assert!((student_t_coverage(1.0, 1) - 0.5).abs() < 1e-15);
        assert!((student_t_coverage(1.5, 2) - 1.5 / (2.0 + 2.25f64).sqrt()).abs() < 1e-15);
        assert_eq!(erfc(0.0), 1.0);
        assert!((erfc(-1.0) - 1.842_700_792_949_715).abs() < 1e-15);
        assert!((erfc(3.0) - 2.209_049_699_858_544e-5).abs() < 1e-19);
    }
}
