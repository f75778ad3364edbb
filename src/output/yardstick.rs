//! The Monte Carlo yardstick: Monte Carlo's RMSE against its sample count
//! `N`, fitted by a power law, and the `N` at which it equals a method's
//! RMSE; Monte Carlo's time against `N`, fitted by a line, and the
//! method's speed-up over Monte Carlo at that `N`.

use serde::{Deserialize, Serialize};

/// `y = a · N^b`, fitted by least squares on `(ln N, ln y)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PowerLaw {
    /// The factor `a`.
    pub a: f64,
    /// The exponent `b` (about `−½` for Monte Carlo's RMSE).
    pub b: f64,
}

impl PowerLaw {
    /// The least-squares fit to the points `(N, y)` with `N > 0` and `y > 0`
    /// (others are skipped); `None` with fewer than two such points of
    /// distinct `N`, or where `a` is beyond `f64` (`0` or infinite: a
    /// curve falling or rising by hundreds of orders of magnitude).
    #[must_use]
    pub fn fit(points: &[(f64, f64)]) -> Option<PowerLaw> {
        let logs: Vec<(f64, f64)> = points
            .iter()
            .filter(|(n, y)| *n > 0.0 && *y > 0.0 && n.is_finite() && y.is_finite())
            .map(|(n, y)| (n.ln(), y.ln()))
            .collect();
        let (b, ln_a) = least_squares(&logs)?;
        let a = ln_a.exp();
        (a.is_finite() && a > 0.0).then_some(PowerLaw { a, b })
    }

    /// `a · N^b`.
    #[must_use]
    pub fn at(&self, n: f64) -> f64 {
        self.a * n.powf(self.b)
    }

    /// The `N` with `a · N^b = y`; `None` where the law is flat or `y ≤ 0`.
    #[must_use]
    pub fn solve(&self, y: f64) -> Option<f64> {
        if y.is_nan() || y <= 0.0 || self.b == 0.0 {
            return None;
        }
        let n = (y / self.a).powf(1.0 / self.b);
        n.is_finite().then_some(n)
    }
}

/// `y = c + d · N`, fitted by least squares.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Line {
    /// The intercept `c`.
    pub c: f64,
    /// The slope `d`.
    pub d: f64,
}

impl Line {
    /// The least-squares fit to `(N, y)`; `None` with fewer than two
    /// distinct `N`.
    #[must_use]
    pub fn fit(points: &[(f64, f64)]) -> Option<Line> {
        let (d, c) = least_squares(points)?;
        Some(Line { c, d })
    }

    /// `c + d · N`.
    #[must_use]
    pub fn at(&self, n: f64) -> f64 {
        self.c + self.d * n
    }
}

/// Slope and intercept of the least-squares line through `points`.
fn least_squares(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    (slope.is_finite() && intercept.is_finite()).then_some((slope, intercept))
}

/// The Monte Carlo sample count of equal RMSE.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "n", rename_all = "lowercase")]
pub enum Equal {
    /// Within the measured range: the fitted `N` (not rounded).
    At(f64),
    /// Below the smallest `N` measured: the method is worse than Monte
    /// Carlo with that many samples.
    Below(u32),
    /// Above the largest `N` measured: the method is better than Monte
    /// Carlo with that many samples.
    Above(u32),
}

impl std::fmt::Display for Equal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Equal::At(n) if *n < 100.0 => write!(f, "{n:.1}"),
            Equal::At(n) => write!(f, "{n:.0}"),
            Equal::Below(n) => write!(f, "< {n}"),
            Equal::Above(n) => write!(f, "> {n}"),
        }
    }
}

/// Monte Carlo's curves on one scene: RMSE and time against `N`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Yardstick {
    /// The sample counts measured, increasing.
    pub counts: Vec<u32>,
    /// The fitted RMSE over every receiver.
    pub rmse: PowerLaw,
    /// The fitted RMSE over the exact penumbra.
    pub rmse_penumbra: Option<PowerLaw>,
    /// The fitted time in seconds.
    pub seconds: Line,
}

impl Yardstick {
    /// The yardstick from Monte Carlo's measurements `(N, RMSE all, RMSE
    /// penumbra, seconds)`; `None` with fewer than two distinct `N` or no
    /// positive RMSE.
    #[must_use]
    pub fn new(points: &[(u32, f64, f64, f64)]) -> Option<Yardstick> {
        let mut counts: Vec<u32> = points.iter().map(|p| p.0).collect();
        counts.sort_unstable();
        counts.dedup();
        let n = |p: &(u32, f64, f64, f64)| f64::from(p.0);
        let all: Vec<(f64, f64)> = points.iter().map(|p| (n(p), p.1)).collect();
        let pen: Vec<(f64, f64)> = points.iter().map(|p| (n(p), p.2)).collect();
        let time: Vec<(f64, f64)> = points.iter().map(|p| (n(p), p.3)).collect();
        Some(Yardstick {
            rmse: PowerLaw::fit(&all)?,
            rmse_penumbra: PowerLaw::fit(&pen),
            seconds: Line::fit(&time)?,
            counts,
        })
    }

    /// The `N` at which the fitted `law` equals `rmse`, or the side of the
    /// measured range it falls on.
    #[must_use]
    pub fn equal(&self, law: &PowerLaw, rmse: f64) -> Option<Equal> {
        let (&lo, &hi) = (self.counts.first()?, self.counts.last()?);
        if rmse <= 0.0 {
            return Some(Equal::Above(hi));
        }
        let n = law.solve(rmse)?;
        Some(if n < f64::from(lo) {
            Equal::Below(lo)
        } else if n > f64::from(hi) {
            Equal::Above(hi)
        } else {
            Equal::At(n)
        })
    }

    /// Monte Carlo's fitted time at `equal` over `seconds`, where `equal`
    /// is within the measured range.
    #[must_use]
    pub fn speedup(&self, equal: Equal, seconds: f64) -> Option<f64> {
        match equal {
            Equal::At(n) if seconds > 0.0 => {
                let s = self.seconds.at(n) / seconds;
                (s.is_finite() && s > 0.0).then_some(s)
            }
            _ => None,
        }
    }
}

/// The Monte Carlo sample counts of the default yardstick: 2, 4, …, 4096.
#[must_use]
pub fn default_mc() -> Vec<u32> {
    (1..=12).map(|k| 1u32 << k).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_power_law_of_an_exact_curve_is_recovered() {
        // RMSE = 0.4 / √N with a wobble that averages out in log space.
        let points: Vec<(u32, f64, f64, f64)> = (1..=12)
            .map(|k| {
                let n = 1u32 << k;
                let wobble = if k % 2 == 0 { 1.05 } else { 1.0 / 1.05 };
                let r = 0.4 / f64::from(n).sqrt() * wobble;
                (n, r, 2.0 * r, 0.001 + 1e-5 * f64::from(n))
            })
            .collect();
        let y = Yardstick::new(&points).unwrap();
        assert!((y.rmse.b + 0.5).abs() < 0.01, "{:?}", y.rmse);
        assert!((y.rmse.a - 0.4).abs() < 0.02, "{:?}", y.rmse);
        // 0.4/√N = 0.02 at N = 400, between the measured 256 and 512.
        let Some(Equal::At(n)) = y.equal(&y.rmse, 0.02) else {
            panic!("{:?}", y.equal(&y.rmse, 0.02))
        };
        assert!((n - 400.0).abs() < 20.0, "{n}");
        // The time line is exact: 0.001 + 1e-5·400 = 0.005 s; a method
        // taking 0.0005 s is 10× faster.
        let s = y.speedup(Equal::At(400.0), 0.0005).unwrap();
        assert!((s - 10.0).abs() < 1e-9, "{s}");
        // Outside the measured range: stated, not extrapolated.
        assert_eq!(y.equal(&y.rmse, 0.9), Some(Equal::Below(2)));
        assert_eq!(y.equal(&y.rmse, 1e-5), Some(Equal::Above(4096)));
        assert_eq!(y.speedup(Equal::Above(4096), 0.001), None);
        assert_eq!(Equal::Below(2).to_string(), "< 2");
        assert_eq!(Equal::Above(4096).to_string(), "> 4096");
    }

    #[test]
    fn a_fit_beyond_f64_is_none() {
        // ln a = 744: a = e^744 overflows; and its mirror underflows to 0.
        let tiny = f64::from_bits(1);
        assert_eq!(PowerLaw::fit(&[(2.0, 1.0), (4.0, tiny)]), None);
        assert_eq!(PowerLaw::fit(&[(2.0, tiny), (4.0, 1.0)]), None);
        let law = PowerLaw::fit(&[(2.0, 1.0), (4.0, 1e-300)]).unwrap();
        assert!(law.a.is_finite() && law.a > 1e299, "{law:?}");
    }

    #[test]
    fn a_curve_that_is_not_monotone_is_still_fitted() {
        // Sample to sample the RMSE may rise; the fit follows the trend.
        let points = [
            (2, 0.30, 0.5, 0.01),
            (4, 0.31, 0.5, 0.02),
            (8, 0.15, 0.3, 0.04),
            (16, 0.16, 0.3, 0.08),
        ];
        let y = Yardstick::new(&points).unwrap();
        assert!(y.rmse.b < -0.3 && y.rmse.b > -0.7, "{:?}", y.rmse);
        assert!(Yardstick::new(&points[..1]).is_none());
    }
}
