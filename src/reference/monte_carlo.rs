//! The [Monte Carlo reference](crate::definitions#exact-and-monte-carlo-references): `V(p)` by sampling the light's
//! emitting measure ([`Light::emitter`]) and casting exact occlusion rays
//! ([`Bvh::segment_unoccluded`]), with a standard error that is valid for
//! stratified samples.
//!
//! # Estimator
//!
//! Randomised quasi-Monte Carlo with independent replicates (Owen, "Monte
//! Carlo Theory, Methods and Examples", §17.2): the `N` samples are split
//! into `K = min(REPLICATES, N)` replicates of `m = ⌈N/K⌉` points each (so
//! `K·m ≥ N` rays are cast). Replicate `r` is the first `m` points of the
//! 2D Sobol' sequence (a (0, 2)-sequence: van der Corput in `s.x`, Sobol's
//! second dimension in `s.y`), each dimension Owen-scrambled with the hashed
//! nested uniform scramble of Burley ("Practical Hash-based Owen
//! Scrambling", JCGT 2020; hash constants of Vegdahl 2021), then XORed with a
//! uniform random digital shift and jittered below the 32-bit grid. The
//! shift makes each point exactly uniform on `[0, 1)²` (to `2⁻⁵²`), so each
//! replicate mean `V̂_r` is unbiased, while the scramble keeps the
//! replicate's points stratified (each elementary interval of the net holds
//! its share). Replicates use independent random seeds, so the `V̂_r` are
//! i.i.d., and
//!
//! - `visibility = (1/K) Σ V̂_r`,
//! - `stderr = s/√K`, `s²` the sample variance of the `K` replicate means.
//!
//! The per-sample variance `V̂(1 − V̂)/N` would *not* be valid: stratified
//! samples are dependent, and their error is usually far below (sometimes,
//! for unlucky alignments, above) the i.i.d. formula. `stderr` is itself
//! estimated from `K − 1` degrees of freedom: `(V̂ − V)/stderr` follows
//! roughly Student's `t` with `K − 1 = 15` degrees of freedom, so tests
//! should use `t` quantiles (`P(|t₁₅| < 2) ≈ 0.936`).
//!
//! Sample patterns are *not* shared between receivers: the replicates'
//! seeds come from SplitMix64 keyed by ([`Options::seed`], the bits of `p`).
//! Errors at different receivers are then independent, so error statistics
//! aggregated over receivers (RMS error, per-point tests with a Šidák
//! correction) mean what they say, and images show noise rather than a
//! pattern that moves coherently across the receiver plane. The result
//! still depends only on the seed and `p`: deterministic, bit-identical for
//! any thread count or order of receivers.
//!
//! A segment light uses only `s.x`: a scrambled van der Corput sequence,
//! stratified in 1D. A point light casts one ray: `V ∈ {0, 1}`, `stderr = 0`.
//!
//! # Cost
//!
//! Each sample is the exact answer of its occlusion ray
//! ([`Bvh::segment_unoccluded`]), but with at least 32 samples on any
//! light but a point most samples are decided without casting it. Once
//! per receiver the triangles that can hide part of the light from it are
//! culled with the BVH, and each one's image on the light is written as
//! three linear edge functions of the light's plane coordinates (for a
//! segment, of its one coordinate, on the plane through it facing the
//! receiver), with margins that bound every rounding between them and the
//! exact determinants at the points the samples map to. A sample whose
//! (polynomially approximated) coordinates lie certainly outside every
//! image is unoccluded; one certainly inside the image of a triangle that
//! lies certainly between the receiver and the light is occluded; the
//! others — within about `10⁻⁵` of the light's radius from an image's
//! edge, or under a triangle reaching the light's depth — cast their ray. The
//! images are binned on a grid of the light's plane, a cell inside one
//! image needing no test at all, and a receiver whose cells all hold no
//! image, or are all inside one, computing no sample at all. The estimates
//! are therefore the same, bit for bit, as casting every ray (tested
//! sample by sample against the rays on scenes built to put corners and
//! edges exactly on sample rays). Where
//! the set-up would cost more than the rays it saves — past `samples/2`
//! candidate triangles, or 8 cell tests per sample, as under a pile of
//! thousands of occluders — and where its margins are not proven (a
//! receiver within 0.06° of the light's plane or a segment's line,
//! coordinates beyond `±10³⁰` or a million times the light's depth),
//! every ray is cast. Measured figures: `benches/README.md`.

mod binned;

use crate::bvh::Bvh;
use crate::scene::{Emitter, Light, ReceiverError};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Independent replicates of the scrambled point set (see the module docs).
pub const REPLICATES: u32 = 16;

/// The fewest samples accepted: two replicates are needed for a standard
/// error.
pub const MIN_SAMPLES: u32 = 2;

/// The seed of [`Options::new`].
pub const DEFAULT_SEED: u64 = 0x5EED_0F5F_7AD0_0001;

/// A Monte Carlo estimate of `V(p)` and its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The estimate of `V(p)`, in `[0, 1]`.
    pub visibility: f64,
    /// Its standard error (see the module docs): finite, `≥ 0`; `0` when
    /// every replicate agrees (in particular for a point light).
    pub stderr: f64,
}

/// Monte Carlo options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Samples per receiver, at least [`MIN_SAMPLES`]; rounded up to a
    /// multiple of the replicate count `min(REPLICATES, samples)`.
    pub samples: u32,
    /// Seed of the sample sequence; default [`DEFAULT_SEED`].
    pub seed: u64,
}

impl Options {
    /// `samples` per receiver with the [`DEFAULT_SEED`].
    #[must_use]
    pub fn new(samples: u32) -> Options {
        Options {
            samples,
            seed: DEFAULT_SEED,
        }
    }

    /// The same options with another seed.
    #[must_use]
    pub fn with_seed(self, seed: u64) -> Options {
        Options { seed, ..self }
    }
}

/// Why no estimate was made.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The receiver cannot see the light's measure ([`Light::emitter`]).
    Receiver(ReceiverError),
    /// [`Options::samples`] is below [`MIN_SAMPLES`].
    TooFewSamples {
        /// The count given.
        samples: u32,
    },
}

impl_error!(
    Error,
    |error, f| match error {
        Error::Receiver(e) => e.fmt(f),
        Error::TooFewSamples { samples } => write!(
            f,
            "Monte Carlo needs at least {MIN_SAMPLES} samples, got {samples}"
        ),
    },
    source = |error| match error {
        Error::Receiver(e) => Some(e),
        Error::TooFewSamples { .. } => None,
    }
);

impl From<ReceiverError> for Error {
    fn from(e: ReceiverError) -> Error {
        Error::Receiver(e)
    }
}

/// `V(p)` by light sampling (see the module docs for the estimator): casts
/// `K·⌈samples/K⌉` rays, `K = min(REPLICATES, samples)`, or one for a point
/// light. The visibility is in `[0, 1]` and the standard error finite;
/// never NaN.
///
/// # Errors
/// [`Error::TooFewSamples`] when `options.samples < MIN_SAMPLES` (checked
/// first, for every light); [`Error::Receiver`] as [`Light::emitter`], and
/// [`ReceiverError::OutOfRange`] when a coordinate of the receiver, the
/// occluders or the light exceeds `10⁹⁰` (the exact segment test's
/// domain: a light `10¹⁵⁰` away would be sampled by rays whose answers
/// are not exact).
pub fn visibility(
    bvh: &Bvh,
    light: &Light,
    p: DVec3,
    options: &Options,
) -> Result<Estimate, Error> {
    if options.samples < MIN_SAMPLES {
        return Err(Error::TooFewSamples {
            samples: options.samples,
        });
    }
    let emitter = light.emitter(p)?;
    if out_of_range(bvh, &emitter, p) {
        return Err(Error::Receiver(ReceiverError::OutOfRange));
    }
    Ok(emitter_visibility(bvh, &emitter, p, options))
}

/// Whether a coordinate of the receiver, the occluders or the light
/// (centre plus extent) exceeds `10⁹⁰`, the domain of the exact segment
/// test every sample's ray is decided by: beyond it (a light `10¹⁵⁰`
/// away) the rays' answers are not exact, and [`visibility`] refuses the
/// receiver ([`ReceiverError::OutOfRange`]).
pub(crate) fn out_of_range(bvh: &Bvh, emitter: &Emitter, p: DVec3) -> bool {
    let (t, l) = super::exact::magnitudes(bvh, emitter, p);
    t.is_nan() || l.is_nan() || t.max(l) > 1e90
}

/// [`visibility`] for a receiver whose view of the light is already known:
/// `emitter` must be `light.emitter(p)` for the scene's light (the
/// renderer's methods get it once per receiver from
/// `method::run`). A sample count below
/// [`MIN_SAMPLES`] is raised to it.
#[must_use]
pub fn emitter_visibility(bvh: &Bvh, emitter: &Emitter, p: DVec3, options: &Options) -> Estimate {
    if let Emitter::Point(x) = emitter {
        let visible = bvh.segment_unoccluded(p, x.position());
        return Estimate {
            visibility: if visible { 1.0 } else { 0.0 },
            stderr: 0.0,
        };
    }
    let (k, m, replicates) = replicates(p, options);
    let mut means = [0.0f64; REPLICATES as usize];
    let samples = k * m;
    BINNED.with_borrow_mut(|binned| {
        // Where the set-up declines, every sample casts its ray.
        binned.build(bvh, emitter, p, samples, binned::grid_cells(samples));
        for (mean, replicate) in means.iter_mut().zip(replicates) {
            let visible = binned.count_unoccluded(&replicate, m, |s| {
                bvh.segment_unoccluded(p, emitter.point_at(s))
            });
            *mean = f64::from(visible) / f64::from(m);
        }
    });
    let means = &means[..k as usize];
    let kf = f64::from(k);
    let v = means.iter().sum::<f64>() / kf;
    let ss = means.iter().map(|&x| (x - v) * (x - v)).sum::<f64>();
    Estimate {
        visibility: v.clamp(0.0, 1.0),
        stderr: (ss / (kf - 1.0) / kf).sqrt(),
    }
}

/// The light points [`emitter_visibility`] tests for receiver `p`, in the
/// order it tests them (replicate by replicate): the segments from `p` to
/// these are its rays. For a point light, its one point. A sample count
/// below [`MIN_SAMPLES`] is raised to it, as there. For tracing the same
/// rays elsewhere (another ray tracer, a GPU) and comparing answers or
/// speed ray for ray (`examples/mc_corpus.rs` writes them for Embree).
pub fn sample_points<'a>(
    emitter: &'a Emitter,
    p: DVec3,
    options: &Options,
) -> impl Iterator<Item = DVec3> + 'a {
    let (_, m, replicates) = replicates(p, options);
    let area = !matches!(emitter, Emitter::Point(_));
    let points = replicates
        .filter(move |_| area)
        .flat_map(move |replicate| (0..m).map(move |i| emitter.point_at(replicate.point(i))));
    let point = match emitter {
        Emitter::Point(x) => Some(x.position()),
        _ => None,
    };
    point.into_iter().chain(points)
}

/// The replicate count `K`, the samples per replicate `m`, and the
/// replicates of receiver `p` (see the module docs).
fn replicates(p: DVec3, options: &Options) -> (u32, u32, impl Iterator<Item = Replicate>) {
    let samples = options.samples.max(MIN_SAMPLES);
    let k = REPLICATES.min(samples);
    let m = samples.div_ceil(k);
    let mut rng = SplitMix64(receiver_key(options.seed, p));
    (k, m, (0..k).map(move |_| Replicate::new(&mut rng)))
}

/// [`visibility`] for every point, in parallel over receivers (rayon's
/// current pool); each result is bit-identical to a [`visibility`] call.
#[must_use]
pub fn visibility_many(
    bvh: &Bvh,
    light: &Light,
    points: &[DVec3],
    options: &Options,
) -> Vec<Result<Estimate, Error>> {
    points
        .par_iter()
        .map(|&p| visibility(bvh, light, p, options))
        .collect()
}

std::thread_local! {
    /// Each thread's decision structure, reused from receiver to receiver.
    static BINNED: std::cell::RefCell<binned::Binned> = std::cell::RefCell::default();
}

/// SplitMix64 (Steele, Lea, Flood 2014).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix64(self.0)
    }
}

/// SplitMix64's finaliser.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The stream key of receiver `p` under `seed`.
fn receiver_key(seed: u64, p: DVec3) -> u64 {
    let h = mix64(p.x.to_bits() ^ mix64(p.y.to_bits() ^ mix64(p.z.to_bits())));
    mix64(seed ^ h)
}

/// One replicate's randomisation: per dimension an Owen-scramble seed and a
/// digital shift, and a key for the sub-grid jitter.
struct Replicate {
    scramble: [u32; 2],
    shift: [u32; 2],
    jitter: u64,
}

impl Replicate {
    fn new(rng: &mut SplitMix64) -> Replicate {
        let (a, b) = (rng.next(), rng.next());
        Replicate {
            scramble: [a as u32, (a >> 32) as u32],
            shift: [b as u32, (b >> 32) as u32],
            jitter: rng.next(),
        }
    }

    /// Point `i` in `[0, 1)²`.
    fn point(&self, i: u32) -> DVec2 {
        self.point_in(i, self.grid(i))
    }

    /// The cell of point `i` on the `2³²` grid: the point lies in
    /// `[g/2³², (g + 1)/2³²)` on each axis.
    #[inline]
    fn grid(&self, i: u32) -> [u32; 2] {
        [
            self.scrambled(0, i),
            self.scrambled(1, sobol_second_reversed(i)),
        ]
    }

    /// [`Replicate::grid`] of points `0, 1, …` (as many as `x` holds):
    /// first coordinates into `x`, second into `y` unless `y` is empty (a
    /// segment's points need the first alone). Straight loops over the
    /// points, which the compiler vectorises; the same values as
    /// [`Replicate::grid`], bit for bit.
    #[inline(always)]
    fn grids(&self, x: &mut [u32], y: &mut [u32]) {
        for (i, g) in (0..).zip(x.iter_mut()) {
            *g = self.scrambled(0, i);
        }
        // Sobol's table of the low byte, XORed with the higher bytes' entry
        // shared by each run of 256 points.
        for (run, g) in (0..).zip(y.chunks_mut(256)) {
            let high = sobol_second_reversed(run << 8);
            for (g, &low) in g.iter_mut().zip(&SOBOL_SECOND_REVERSED[0]) {
                *g = self.scrambled(1, low ^ high);
            }
        }
    }

    /// Dimension `d` of [`Replicate::grid`] from its digits bit-reversed
    /// (as `owen_scramble` hashes them: van der Corput's are `i` itself,
    /// Sobol's second dimension [`sobol_second_reversed`]): scrambled and
    /// shifted.
    #[inline(always)]
    fn scrambled(&self, d: usize, digits: u32) -> u32 {
        owen_scramble_reversed(digits, self.scramble[d]) ^ self.shift[d]
    }

    /// Point `i`, whose grid cell is `grid` ([`Replicate::grid`]).
    fn point_in(&self, i: u32, grid: [u32; 2]) -> DVec2 {
        let h = mix64(self.jitter ^ u64::from(i));
        let coordinate = |d: usize| {
            // 20 jitter bits below the 32-bit grid: the sum is exact and < 1.
            let jitter = f64::from(((h >> (32 * d)) & 0xF_FFFF) as u32) / f64::from(1u32 << 20);
            (f64::from(grid[d]) + jitter) / 4_294_967_296.0
        };
        DVec2::new(coordinate(0), coordinate(1))
    }
}

/// Sobol's second dimension as 32 bits, bit-reversed: direction numbers
/// `v₁ = 2³¹`, `v_{k+1} = v_k ⊕ (v_k ≫ 1)` (the Pascal matrix mod 2). Linear
/// over GF(2) in the bits of `i`: the XOR of one table entry per byte.
fn sobol_second_reversed(i: u32) -> u32 {
    let b = i.to_le_bytes();
    SOBOL_SECOND_REVERSED[0][usize::from(b[0])]
        ^ SOBOL_SECOND_REVERSED[1][usize::from(b[1])]
        ^ SOBOL_SECOND_REVERSED[2][usize::from(b[2])]
        ^ SOBOL_SECOND_REVERSED[3][usize::from(b[3])]
}

/// `SOBOL_SECOND_REVERSED[k][b]`: [`sobol_second`] of `b << 8k`,
/// bit-reversed.
static SOBOL_SECOND_REVERSED: [[u32; 256]; 4] = {
    let mut table = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            table[k][b] = sobol_second((b as u32) << (8 * k)).reverse_bits();
            b += 1;
        }
        k += 1;
    }
    table
};

/// Sobol's second dimension as 32 bits (see [`sobol_second_reversed`]).
const fn sobol_second(mut i: u32) -> u32 {
    let (mut v, mut x) = (1u32 << 31, 0u32);
    while i != 0 {
        if i & 1 != 0 {
            x ^= v;
        }
        i >>= 1;
        v ^= v >> 1;
    }
    x
}

/// Burley's scramble of the 32-bit fraction `x` as the papers write it
/// (reverse, hash, reverse): the tests' statement of what
/// [`owen_scramble_reversed`] computes.
#[cfg(test)]
fn owen_scramble(x: u32, seed: u32) -> u32 {
    owen_scramble_reversed(x.reverse_bits(), seed)
}

/// Burley's hashed nested uniform scramble of the 32-bit fraction whose
/// bit reversal is `r` (each output bit depends on the fraction's higher
/// bits only, so nets stay nets), returned as a fraction. Hash of Vegdahl
/// ("Building a Better LK Hash", 2021).
#[inline(always)]
fn owen_scramble_reversed(r: u32, seed: u32) -> u32 {
    let mut x = r;
    x ^= x.wrapping_mul(0x3d20_adea);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6c56);
    x ^= x.wrapping_mul(0x53a2_2864);
    x.reverse_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The points `sample_points` lists are the rays the estimate casts:
    /// counting the unoccluded ones, replicate by replicate, gives the
    /// same estimate bit for bit.
    #[test]
    fn sample_points_are_the_estimates_rays() {
        let light = crate::scene::Light::sphere(DVec3::new(0.2, 0.1, 3.0), 0.6).expect("light");
        let tris = vec![
            [
                DVec3::new(-0.5, -0.5, 1.0),
                DVec3::new(0.6, -0.4, 1.2),
                DVec3::new(0.0, 0.7, 1.1),
            ],
            [
                DVec3::new(0.3, 0.2, 2.0),
                DVec3::new(0.9, 0.3, 2.1),
                DVec3::new(0.5, 0.8, 1.9),
            ],
        ];
        let bvh = Bvh::new(crate::bvh::Occluders::from_triangles(tris));
        for (p, samples) in [
            (DVec3::new(0.1, 0.0, 0.0), 4096),
            (DVec3::new(-0.4, 0.3, 0.0), 100),
        ] {
            let options = Options::new(samples);
            let emitter = light.emitter(p).expect("emitter");
            let points: Vec<DVec3> = sample_points(&emitter, p, &options).collect();
            let k = REPLICATES.min(samples) as usize;
            let m = points.len() / k;
            assert_eq!(m * k, points.len());
            assert_eq!(m, samples.div_ceil(k as u32) as usize);
            let means: Vec<f64> = points
                .chunks(m)
                .map(|c| {
                    c.iter().filter(|&&x| bvh.segment_unoccluded(p, x)).count() as f64 / m as f64
                })
                .collect();
            let v = means.iter().sum::<f64>() / k as f64;
            let estimate = emitter_visibility(&bvh, &emitter, p, &options);
            assert_eq!(v.clamp(0.0, 1.0).to_bits(), estimate.visibility.to_bits());
            assert!(estimate.visibility > 0.0 && estimate.visibility < 1.0);
        }
    }

    #[test]
    fn first_points_form_a_net() {
        // The first 2^k points of a (0, 2)-sequence: one per 2^a × 2^(k−a)
        // elementary box, before and after scrambling.
        let replicate = Replicate::new(&mut SplitMix64(7));
        for k in 0..8u32 {
            for a in 0..=k {
                let mut seen = vec![false; 1 << k];
                for i in 0..(1u32 << k) {
                    let s = replicate.point(i);
                    assert!(s.x < 1.0 && s.y < 1.0 && s.x >= 0.0 && s.y >= 0.0);
                    let bx = (s.x * f64::from(1u32 << a)) as usize;
                    let by = (s.y * f64::from(1u32 << (k - a))) as usize;
                    let cell = (bx << (k - a)) | by;
                    assert!(!seen[cell], "k {k} a {a}");
                    seen[cell] = true;
                }
            }
        }
    }

    /// The points are the published construction stated literally: van der
    /// Corput's digits `reverse(i)` and Sobol's second dimension bit by
    /// bit, each scrambled as reverse–hash–reverse, shifted and jittered
    /// (the tables and the cancelled reversals change no bit).
    #[test]
    fn points_follow_the_construction() {
        let mut rng = SplitMix64(0xDEC0DE);
        for _ in 0..8 {
            let replicate = Replicate::new(&mut rng);
            let mut indices: Vec<u32> = (0..4096).collect();
            indices.extend((0..4096).map(|_| rng.next() as u32));
            indices.extend([u32::MAX, 1 << 31, 0xFFFF, 0x0100_0000]);
            for i in indices {
                let digits = [i.reverse_bits(), sobol_second(i)];
                let h = mix64(replicate.jitter ^ u64::from(i));
                let expected: [f64; 2] = std::array::from_fn(|d| {
                    let x = owen_scramble(digits[d], replicate.scramble[d]) ^ replicate.shift[d];
                    let jitter = ((h >> (32 * d)) & 0xF_FFFF) as f64 / f64::from(1u32 << 20);
                    (f64::from(x) + jitter) / 4_294_967_296.0
                });
                let s = replicate.point(i);
                assert_eq!(
                    [s.x.to_bits(), s.y.to_bits()],
                    expected.map(f64::to_bits),
                    "i {i}"
                );
            }
        }
    }

    /// The batched grid cells are the construction's, point by point, for
    /// counts that end anywhere in a run of 256 points and across several
    /// runs; a segment's (no second coordinate) too.
    #[test]
    fn batched_grid_cells_follow_the_construction() {
        let mut rng = SplitMix64(0xBA7C4);
        for n in [1, 2, 3, 17, 255, 256, 257, 511, 700, 1024, 2049] {
            let replicate = Replicate::new(&mut rng);
            let (mut x, mut y) = (vec![0; n], vec![0; n]);
            replicate.grids(&mut x, &mut y);
            for (i, (&gx, &gy)) in (0u32..).zip(x.iter().zip(&y)) {
                let digits = [i.reverse_bits(), sobol_second(i)];
                let expected: [u32; 2] = std::array::from_fn(|d| {
                    owen_scramble(digits[d], replicate.scramble[d]) ^ replicate.shift[d]
                });
                assert_eq!([gx, gy], expected, "n {n}, i {i}");
            }
            let mut first = vec![0; n];
            replicate.grids(&mut first, &mut []);
            assert_eq!(first, x, "n {n}");
        }
    }
}
