//! Deterministic generators of stiff, near-degenerate input, shared by the
//! property tests (`tests/`), the fuzz targets (`fuzz/`) and the benchmarks
//! (`benches/`). Compiled with the `arbitrary` feature (and in unit tests).
//!
//! Everything is driven by [`Rng`], a seeded SplitMix64 stream, so one `u64`
//! seed reproduces a case: proptest draws seeds, a fuzz target reads one from
//! its bytes, a benchmark fixes it. The generators are biased toward the
//! inputs that break geometry code: magnitudes spread log-uniformly over many
//! decades, points a few ulps off a circle or a line, zero-length and
//! enormous edges, exact zeros and boundary values.

pub mod disk;
pub mod light;
pub mod mesh;
pub mod scene;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, fast, well-mixed 64-bit
/// generator; deterministic for a seed.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator seeded with `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in `0..n` (`n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        // Lemire's multiply-shift; the bias is < n / 2⁶⁴, irrelevant here.
        ((self.next_u64() as u128 * n as u128) >> 64) as u64
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A magnitude `10^e` with `e` uniform in `[lo_exp, hi_exp]`: log-uniform
    /// over the decades.
    pub fn log_uniform(&mut self, lo_exp: f64, hi_exp: f64) -> f64 {
        10f64.powf(self.uniform(lo_exp, hi_exp))
    }

    /// A random sign.
    pub fn sign(&mut self) -> f64 {
        if self.next_u64() & 1 == 0 {
            1.0
        } else {
            -1.0
        }
    }

    /// `x` moved by `k` ulps (`k` in `-ulps..=ulps`), toward ±∞.
    pub fn nudge(&mut self, x: f64, ulps: u64) -> f64 {
        let k = self.below(2 * ulps + 1) as i64 - ulps as i64;
        step_ulps(x, k)
    }
}

/// `x` moved `k` representable values up (`k > 0`) or down (`k < 0`);
/// non-finite `x` is returned unchanged.
#[must_use]
pub fn step_ulps(x: f64, k: i64) -> f64 {
    if !x.is_finite() {
        return x;
    }
    let mut y = x;
    for _ in 0..k.unsigned_abs() {
        y = if k > 0 { y.next_up() } else { y.next_down() };
    }
    y
}
