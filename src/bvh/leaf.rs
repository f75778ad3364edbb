//! The leaves of the occlusion tree: up to [`PACK`] triangles in
//! structure-of-arrays `f32`, tested together by the sign-of-volumes test
//! evaluated in `f32` with a proven error bound. A lane whose every sign
//! the bound makes certain is decided there; any other lane goes to the
//! exact `f64` test ([`segment_blocked`]). The answer is therefore exactly
//! the exact test's.
//!
//! # The test
//!
//! The open segment `(P, X)` meets the closed triangle `(A, B, C)` iff the
//! three edge volumes `e₀ = det[X − P; A − P; B − P]`, `e₁ = det[X − P;
//! B − P; C − P]`, `e₂ = det[X − P; C − P; A − P]` have no strictly
//! opposite pair and are not all zero, and the plane volumes `s_P =
//! det[A − P; B − P; C − P]` and `s_X = det[A − X; B − X; C − X]` are
//! nonzero and of opposite signs ([`segment_blocked`]'s definition). With
//! `d = X − P`, `a = A − P`, the edges `E_ab = B − A`, `E_ca = A − C` and
//! the normal `N = E_ca × E_ab`, the same determinants are
//!
//! - `e₀ = E_ab · w`, `e₂ = E_ca · w` with `w = d × a` (`e₀ = d · (a ×
//!   b) = d · (a × E_ab)`, and `c × E_ca = a × E_ca` as `c = a − E_ca`),
//! - `e₁ = d · N − e₀ − e₂` (the three sum to `d · (a × b + b × c + c ×
//!   a) = d · N`),
//! - `s_P = a · N` and `s_X = s_P − d · N` (`det[A − Q; B − Q; C − Q] =
//!   det[A; B; C] − Q · N` for any point `Q`):
//!
//! one cross product a lane from the corner `A` shared by the edges, three
//! dot products for the edges and one for the planes, all of them products
//! of a difference from `P` and of edges, whose errors scale with the
//! triangle's size rather than with its distance. A pack stores `A`,
//! `E_ab` and `E_ca` lane by lane in `f32` (see [`Packs`]).
//!
//! # The bound
//!
//! Let `u = 2⁻²⁴`, `γₙ = n u / (1 − n u)` and `K = 1 + γ₂`. The stored
//! values are `A′ = fl₃₂(A)` (`ε_c` bounding `|A − A′|∞` over the pack)
//! and `E′ = fl₃₂(fl₆₄(B − A))` (and `E_ca`'s alike; `ε_E` bounding
//! `|E′ − E|∞` over the pack: the exact `|E′ − fl₆₄(B − A)|∞` plus
//! `2⁻⁵²|fl₆₄(B − A)|∞` for the `f64` difference); the segment's are `P′ =
//! fl₃₂(P)` and `d′ = fl₃₂(fl₆₄(X − P))`, with `ε_r` bounding `|P − P′|∞`
//! and `ε_d` bounding `|d′ − d|∞` (all computed exactly in `f64` and
//! rounded up). The test computes, in `f32`, `a = fl(A′ − P′)`, `w =
//! fl(d′ × a)`, `N = fl(E′_ca × E′_ab)` (each cross product's components
//! with two products and a difference), the dot products with three
//! products and two sums left to right, then `e₁` and `s_X` by the
//! differences above. With `M` the pack's largest corner magnitude (all
//! three corners, rounded to `f32`), `R = |P′|∞`, `S = M + R` and `L` the
//! pack's largest stored edge `|E′|∞`:
//!
//! - `Â = S (1 + u) + ε_c + ε_r` bounds both the computed `|a|∞` and the
//!   true `|A − P|∞`, and `ε_a = u S + ε_c + ε_r` their difference (one
//!   rounding of a difference of stored values, plus the roundings of the
//!   corner and the endpoint);
//! - `Ê = L + ε_E` bounds the stored and the true edges;
//! - `D̂ = |d′|∞ + ε_d` bounds the computed and the true `d`.
//!
//! A component of a computed cross product of rows bounded by `x̂` and `ŷ`
//! is within `2 γ₂ x̂ ŷ` of the cross product of the computed rows, a
//! computed dot product within `3 γ₃ x̂ ŷ` of theirs (Higham §3.1); and a
//! product of two rows off by `δ_x`, `δ_y` is off by at most `δ_x ŷ + x̂
//! δ_y` a term. So `w` is within `δ_w = 2 γ₂ D̂ Â + 2 (ε_d Â + D̂ ε_a)` of
//! `d × a`, both bounded by `W = 2 K D̂ Â`; `N` within `δ_N = 2 γ₂ Ê² + 4 Ê
//! ε_E` of the true normal, both bounded by `N̂ = 2 K Ê²`; and (with
//! `γ₃ K + γ₂ ≤ γ₅`)
//!
//! - the computed `e₀` and `e₂` are within `3 γ₃ Ê W + 3 (ε_E W + Ê δ_w) ≤
//!   B_e = 6 (γ₅ D̂ Â Ê + K D̂ Â ε_E + ε_d Â Ê + D̂ ε_a Ê)` of the exact
//!   ones, and at most `6 (1 + γ₅) D̂ Â Ê` in magnitude;
//! - the computed `d · N` within `B_n = 6 (γ₅ D̂ Ê² + K ε_d Ê² + 2 D̂ Ê
//!   ε_E)`, at most `6 (1 + γ₅) D̂ Ê²`; the computed `s_P` within `B_p =
//!   6 (γ₅ Â Ê² + K ε_a Ê² + 2 Â Ê ε_E)`, at most `6 (1 + γ₅) Â Ê²`;
//! - the computed `e₁` within `B_E = 2 B_e + B_n + 2 ρ D̂ Ê (Ê + 2 Â)`, the
//!   last term the two subtractions' roundings (`u (2 + u)` times the sum
//!   of the three magnitudes), with `ρ = 6 u (1 + u) (1 + γ₅)`; the
//!   computed `s_X` within `B_X = B_p + B_n + ρ Ê² (Â + D̂)`.
//!
//! The test compares all three edge volumes against `B_E` and both plane
//! volumes against `B_X`, the larger of each kind; gathered by factors
//! (`K ≤ 2`, so `Ê²`'s factor in `B_E` is below `ÂÊ`'s, `σ = (12 γ₅ + 4
//! ρ) D̂ + 12 ε_d`),
//!
//! `B_E ≤ σ Ê (Â + Ê) + 12 K D̂ (ε_E (Â + Ê) + ε_a Ê)`,
//!
//! `B_X = (Â + D̂) Q₁ + (ε_a + ε_d) Q₂`, `Q₁ = (6 γ₅ + ρ) Ê² + 12 Ê ε_E`, `Q₂
//! = 6 K Ê²`;
//!
//! both taken plus `F = 2⁻¹⁰⁰`, which covers underflow: the test runs only
//! where `M` and the endpoints' magnitudes are at most `2⁴⁰` (elsewhere
//! every lane goes to the exact test), so `Â`, `Ê` and `D̂` are below
//! `2⁴¹ (1 + 2⁻²⁰)`, every computed value below `2¹²⁸` (the largest, `e₁`,
//! below `18 · 2¹²³ (1 + 2⁻¹⁸)`: no overflow), and the absolute error of
//! the products that underflow (at most `2⁻¹⁵⁰` each, carried through by
//! factors below `2⁴²`) stays below `2⁻¹⁰⁴`.
//!
//! # Evaluating the bounds
//!
//! `Â` and `ε_a` are sums of a pack's part and a segment's: `Â = m + r`,
//! `ε_a = m′ + r′` with `m = M (1 + u) + ε_c`, `m′ = u M + ε_c`, `r = R (1 +
//! u) + ε_r`, `r′ = u R + ε_r`. Multiplied out,
//!
//! `B_E − F ≤ σ (Ê (m + Ê)) + 12 K D̂ (ε_E (m + Ê) + Ê m′) + (σ r + 12 K D̂
//! r′) Ê + (12 K D̂ r) ε_E`,
//!
//! `B_X − F = (m Q₁ + m′ Q₂) + (r + D̂) Q₁ + (r′ + ε_d) Q₂`:
//!
//! each a short sum of products of a pack's terms (computed once, at the
//! build: `Ê (m + Ê)`, `ε_E (m + Ê) + Ê m′`, `Ê`, `ε_E`, and `m Q₁ + m′
//! Q₂`, `Q₁`, `Q₂`) and a segment's (computed once a segment). Every term
//! is nonnegative; each is computed in `f64` from exact inputs (a few
//! roundings of `2⁻⁵³`), widened by `2⁻²²` and rounded up to `f32` (a
//! pack's) or kept in `f64` (a segment's), and the sums, computed in `f64`
//! (three roundings), are widened by `2⁻²²` again before they are rounded
//! to `f32`: the bounds used are at least `B_E` and `B_X`. A pack whose `M`
//! exceeds `2⁴⁰` stores `+∞` for the terms with `m` in them, a segment
//! with an endpoint beyond it does for `r` and `r′`: its bounds are then
//! `+∞` or NaN (a product `0 · ∞`), and no computed volume compares
//! certain against either (the comparisons are ordered), so every lane is
//! uncertain.
//!
//! # Certain lanes
//!
//! A computed volume above its bound is certainly positive, below minus
//! its bound certainly negative. A lane is
//!
//! - *a certain miss* when two edge volumes are certainly of opposite
//!   signs, or both plane volumes are certainly of one sign (the segment
//!   ends on one side of the plane);
//! - *a certain hit* when all three edge volumes are certainly of one sign
//!   (so none is zero and none opposite) and the plane volumes are
//!   certainly of opposite signs;
//! - *uncertain* otherwise — a segment grazing an edge or a vertex
//!   (through a shared edge, every edge volume there is zero), ending on
//!   or near the triangle's plane, a degenerate triangle, coordinates
//!   beyond the `f32` test's range — and decided by [`segment_blocked`].
//!
//! Every lane's answer is thus the exact test's. Each lane runs the same
//! `f32` operations in the same order, so the verdicts do not depend on
//! how many lanes are evaluated at once or on the instructions used (the
//! tests compare AVX2's lanes with the portable ones bit for bit).
//!
//! [`segment_blocked`]: crate::kernel::segment::segment_blocked

use super::f32_up;
use super::lanes::Lanes;
use glam::DVec3;

/// Triangles per leaf pack.
pub(super) const PACK: usize = 8;

/// `u = 2⁻²⁴`, the unit roundoff of `f32`.
const U: f64 = 1.0 / (1u32 << 24) as f64;
/// `γ₅ = 5u / (1 − 5u)`.
const GAMMA5: f64 = 5.0 * U / (1.0 - 5.0 * U);
/// `K = 1 + γ₂`.
const K: f64 = 1.0 + 2.0 * U / (1.0 - 2.0 * U);
/// `ρ = 6 u (1 + u) (1 + γ₅)`: the subtractions' roundings.
const RHO: f64 = 6.0 * U * (1.0 + U) * (1.0 + GAMMA5);
/// `F`: the bound's floor, covering underflow.
const FLOOR: f64 = 1.0 / (1u128 << 100) as f64;
/// The largest corner and endpoint magnitude the `f32` test takes, `2⁴⁰`.
const REACH: f64 = (1u64 << 40) as f64;
/// The widening of a bound computed in `f64` before rounding it to `f32`.
const WIDEN: f64 = 1.0 + 1.0 / (1u32 << 22) as f64;

/// Floats of a pack's header: the lane count less one (bits), the edge
/// bound's terms `Ê (m + Ê)`, `ε_E (m + Ê) + Ê m′`, `Ê`, `ε_E` and the
/// plane bound's `m Q₁ + m′ Q₂`, `Q₁`, `Q₂` (see the module docs).
const HEADER: usize = 8;
/// The floats read from a pack's start, at most: the header, nine rows of
/// [`PACK`] lanes each read [`PACK`] floats on, and the occluder indices
/// after them.
const SPAN: usize = HEADER + 9 * PACK + PACK;
/// The rows' vectors: `E_ab`, `E_ca`, then `A`, whose last row's lanes
/// beyond the count read the occluder indices (subnormal floats): it is
/// only subtracted from (a product with a subnormal is slow on x86).
const AB: usize = 0;
const CA: usize = 1;
const CORNER: usize = 2;

/// The leaves' packs, one after another in one array of `f32`, each on a
/// multiple of eight floats (32 bytes): a header of [`HEADER`] floats,
/// then its triangles' edges `E_ab`, `E_ca` and corners `A` rounded to
/// nearest `f32`, row by row (vector `k` of [`AB`], [`CA`], [`CORNER`],
/// axis `a`: row `3k + a`), each row `count` floats long (a lane a
/// triangle), then the triangles' occluder indices (their bits). A row is
/// read as [`PACK`] floats, the lanes beyond `count` being whatever
/// follows (masked off: their verdicts are not used); the array ends with
/// [`SPAN`] floats of padding, so every read stays within it. A pack of
/// `n` triangles takes `32 + 40 n` bytes, rounded up to 32.
#[derive(Debug, Default)]
pub(super) struct Packs {
    data: Vec<f32>,
}

/// One pack of [`Packs`].
#[derive(Clone, Copy)]
pub(super) struct Pack<'a> {
    data: &'a [f32; SPAN],
    count: usize,
}

/// `v − u` rounded to `f32` (from `f64`), and how far it lies from the
/// true difference at most (see the module docs: `ε_E`).
fn stored_edge(u: DVec3, v: DVec3) -> (DVec3, f64) {
    let (difference, stored) = (v - u, (v - u).as_vec3().as_dvec3());
    let slack = difference.abs() / (1u64 << 52) as f64;
    (stored, ((difference - stored).abs() + slack).max_element())
}

impl Packs {
    /// Appends the pack of `triangles` (1 to [`PACK`] of them, finite,
    /// each with its occluder index); returns its index (its start in
    /// units of eight floats). Call [`Packs::finish`] after the last.
    pub(super) fn push(&mut self, triangles: &[([DVec3; 3], u32)]) -> u32 {
        let count = triangles.len();
        assert!((1..=PACK).contains(&count));
        let start = self.data.len();
        assert_eq!(start % 8, 0);
        let (mut magnitude, mut corner_error) = (0.0f64, 0.0f64);
        let (mut edge, mut edge_error) = (0.0f64, 0.0f64);
        let mut rows = [[0.0f32; PACK]; 9];
        for (lane, &([a, b, c], _)) in triangles.iter().enumerate() {
            let corner = a.as_vec3().as_dvec3();
            let (ab, ab_error) = stored_edge(a, b);
            let (ca, ca_error) = stored_edge(c, a);
            for (k, v) in [(CORNER, corner), (AB, ab), (CA, ca)] {
                for axis in 0..3 {
                    rows[3 * k + axis][lane] = v[axis] as f32;
                }
            }
            for v in [a, b, c] {
                magnitude = magnitude.max(v.as_vec3().as_dvec3().abs().max_element());
            }
            // Exact in `f64`: a value less its nearest `f32`.
            corner_error = corner_error.max((a - corner).abs().max_element());
            edge = edge.max(ab.abs().max(ca.abs()).max_element());
            edge_error = edge_error.max(ab_error.max(ca_error));
        }
        self.data.push(f32::from_bits(count as u32 - 1));
        self.data
            .extend(pack_terms(magnitude, corner_error, edge, edge_error));
        for row in &rows {
            self.data.extend_from_slice(&row[..count]);
        }
        self.data
            .extend(triangles.iter().map(|&(_, id)| f32::from_bits(id)));
        self.data.resize(self.data.len().next_multiple_of(8), 0.0);
        (start / 8) as u32
    }

    /// Ends the array with its padding.
    pub(super) fn finish(&mut self) {
        self.data.resize(self.data.len() + SPAN, 0.0);
    }

    /// Pack `at` (an index [`Packs::push`] returned).
    #[inline(always)]
    pub(super) fn get(&self, at: u32) -> Pack<'_> {
        let start = at as usize * 8;
        let data: &[f32; SPAN] = self.data[start..start + SPAN]
            .try_into()
            .expect("within the padding");
        Pack {
            data,
            count: (data[0].to_bits() as usize & (PACK - 1)) + 1,
        }
    }

    /// The bytes the packs take (their indices included).
    pub(super) fn bytes(&self) -> usize {
        self.data.len() * 4
    }
}

/// The pack's terms of the bounds in `f64` from `M`, `ε_c`, `L`, `ε_E`
/// (see the module docs): `Ê (m + Ê)`, `ε_E (m + Ê) + Ê m′`, `Ê`, `ε_E`,
/// then `m Q₁ + m′ Q₂`, `Q₁`, `Q₂`.
fn defined_terms(magnitude: f64, corner_error: f64, edge: f64, edge_error: f64) -> [f64; 7] {
    let (c, e_error) = (corner_error, edge_error);
    let m = magnitude * (1.0 + U) + c;
    let m_error = magnitude * U + c;
    let e = edge + e_error;
    let q1 = (6.0 * GAMMA5 + RHO) * e * e + 12.0 * e * e_error;
    let q2 = 6.0 * K * e * e;
    [
        e * (m + e),
        e_error * (m + e) + e * m_error,
        e,
        e_error,
        m * q1 + m_error * q2,
        q1,
        q2,
    ]
}

/// [`defined_terms`] as stored: widened and rounded up to `f32`; the
/// first of each list `+∞` when `M` is beyond [`REACH`].
fn pack_terms(magnitude: f64, corner_error: f64, edge: f64, edge_error: f64) -> [f32; 7] {
    // All of them far below `f32::MAX` within reach (`M, L ≤ 2⁴¹`), where
    // `f32_up` rounds up.
    let up = |t: f64| f32_up(t * WIDEN);
    let terms = defined_terms(magnitude, corner_error, edge, edge_error).map(up);
    let reach = |t: f32| if magnitude <= REACH { t } else { f32::INFINITY };
    [
        reach(terms[0]),
        terms[1],
        terms[2],
        terms[3],
        reach(terms[4]),
        terms[5],
        terms[6],
    ]
}

impl<'a> Pack<'a> {
    /// Its lanes in use, `1..=PACK`.
    #[inline(always)]
    pub(super) fn count(&self) -> u32 {
        self.count as u32
    }

    /// The occluder index of lane `lane` (below the count).
    #[inline(always)]
    pub(super) fn id(&self, lane: usize) -> u32 {
        self.data[HEADER + 9 * self.count + lane].to_bits()
    }

    /// Vector `k`'s ([`CORNER`], [`AB`], [`CA`]) axis `axis`, lane by lane
    /// (lanes from `count` on are whatever follows).
    #[inline(always)]
    fn row(&self, k: usize, axis: usize) -> &'a [f32; PACK] {
        let at = HEADER + (3 * k + axis) * self.count;
        self.data[at..at + PACK]
            .try_into()
            .expect("within the span")
    }

    /// The edge bound's terms (`Ê (m + Ê)`, `ε_E (m + Ê) + Ê m′`, `Ê`,
    /// `ε_E`).
    #[inline(always)]
    fn edge_terms(&self) -> [f32; 4] {
        [self.data[1], self.data[2], self.data[3], self.data[4]]
    }

    /// The plane bound's terms (`m Q₁ + m′ Q₂`, `Q₁`, `Q₂`).
    #[inline(always)]
    fn plane_terms(&self) -> [f32; 3] {
        [self.data[5], self.data[6], self.data[7]]
    }
}

#[cfg(test)]
impl Pack<'_> {
    /// Vector `k` ([`AB`], [`CA`], [`CORNER`]) of lane `lane` as stored.
    pub(super) fn stored(&self, k: usize, lane: usize) -> DVec3 {
        DVec3::from_array([0, 1, 2].map(|a| f64::from(self.row(k, a)[lane])))
    }

    /// Its occluder indices, lane by lane.
    pub(super) fn ids(&self) -> Vec<u32> {
        (0..self.count).map(|lane| self.id(lane)).collect()
    }

    /// Checks the rows and the bounds' terms against the pack's triangles
    /// (its indices into `triangles`): `A`, `B − A`, `A − C` rounded to
    /// nearest `f32`; with `M`, `ε_c`, `L`, `ε_E` found here, each term at
    /// least the module docs' definition and at most `2⁻²⁰` above it (`+∞`,
    /// the terms with `m`, where `M` is beyond reach).
    pub(super) fn check_terms(&self, triangles: &[[DVec3; 3]]) {
        let (mut magnitude, mut corner_error) = (0.0f64, 0.0f64);
        let (mut edge, mut edge_error) = (0.0f64, 0.0f64);
        for lane in 0..self.count {
            let [a, b, c] = triangles[self.id(lane) as usize];
            let stored: [DVec3; 3] = core::array::from_fn(|k| self.stored(k, lane));
            assert_eq!(stored[CORNER], a.as_vec3().as_dvec3());
            assert_eq!(stored[AB], (b - a).as_vec3().as_dvec3());
            assert_eq!(stored[CA], (a - c).as_vec3().as_dvec3());
            for v in [a, b, c] {
                magnitude = magnitude.max(f64::from(v.as_vec3().abs().max_element()));
            }
            corner_error = corner_error.max((a - stored[CORNER]).abs().max_element());
            for (stored, exact) in [(stored[AB], b - a), (stored[CA], a - c)] {
                edge = edge.max(stored.abs().max_element());
                let error = (stored - exact).abs().max_element();
                edge_error = edge_error.max(error + exact.abs().max_element() * 2f64.powi(-52));
            }
        }
        let defined = defined_terms(magnitude, corner_error, edge, edge_error);
        let stored = [self.edge_terms().as_slice(), self.plane_terms().as_slice()].concat();
        for (k, (&stored, defined)) in stored.iter().zip(defined).enumerate() {
            let stored = f64::from(stored);
            if magnitude > REACH && (k == 0 || k == 4) {
                assert_eq!(stored, f64::INFINITY, "term {k}");
            } else {
                assert!(
                    defined * (1.0 - 1e-12) <= stored
                        && (stored <= defined * (1.0 + 1.0 / f64::from(1u32 << 20))
                            || stored <= f64::from(f32::MIN_POSITIVE)),
                    "term {k}: {stored} against {defined}"
                );
            }
        }
    }
}

/// What the leaf test needs of a segment `(p, x)`, computed once a ray
/// (on its first leaf): the origin and direction in `f32`, each axis in
/// every lane, and the segment's terms of the bounds.
pub(super) struct LeafRay<F> {
    p: [F; 3],
    d: [F; 3],
    /// The segment's terms of the bounds (see [`Terms`]).
    edge: [f64; 4],
    plane: [f64; 2],
}

/// The scalars of a [`LeafRay`].
struct Terms {
    p: [f32; 3],
    d: [f32; 3],
    /// `σ`, `12 K D̂`, `σ r + 12 K D̂ r′`, `12 K D̂ r`: the edge bound's
    /// factors of a pack's `Ê (m + Ê)`, `ε_E (m + Ê) + Ê m′`, `Ê`, `ε_E`
    /// (see the module docs).
    edge: [f64; 4],
    /// `r + D̂`, `r′ + ε_d`: the plane bound's factors of a pack's `Q₁`,
    /// `Q₂`; `+∞` where an endpoint is beyond [`REACH`].
    plane: [f64; 2],
}

/// The scalars of the segment `(p, x)` for [`LeafRay::new`]: out of line,
/// so that they are computed only for segments that reach a leaf (inline,
/// the compiler computed them ahead of the walk for every segment).
#[inline(never)]
fn terms(p: DVec3, x: DVec3) -> Terms {
    let d = x - p;
    let (p32, d32) = (p.as_vec3(), d.as_vec3());
    // Exact in `f64`: a value less its nearest `f32`.
    let end_error = (p - p32.as_dvec3()).abs().max_element() * WIDEN;
    let length_error =
        ((d - d32.as_dvec3()).abs() + d.abs() * (2.0 * f64::EPSILON)).max_element() * WIDEN;
    let length = f64::from(d32.abs().max_element()) + length_error;
    let near = f64::from(p32.abs().max_element());
    let reach = near.max(x.abs().max_element());
    let (r, r_error) = if reach <= REACH {
        (near * (1.0 + U) + end_error, near * U + end_error)
    } else {
        (f64::INFINITY, f64::INFINITY)
    };
    let sigma = (12.0 * GAMMA5 + 4.0 * RHO) * length + 12.0 * length_error;
    let k_length = 12.0 * K * length;
    Terms {
        p: p32.to_array(),
        d: d32.to_array(),
        edge: [
            sigma,
            k_length,
            sigma * r + k_length * r_error,
            k_length * r,
        ],
        plane: [r + length, r_error + length_error],
    }
}

impl<F: Copy> LeafRay<F> {
    /// The constants of the segment `(p, x)` (finite endpoints), on the
    /// lanes `s`.
    #[inline(always)]
    pub(super) fn new<S: Lanes<PACK, F = F>>(s: S, p: DVec3, x: DVec3) -> LeafRay<F> {
        let t = terms(p, x);
        LeafRay {
            p: splat(s, t.p),
            d: splat(s, t.d),
            edge: t.edge,
            plane: t.plane,
        }
    }

    /// The bound `B_E` of `pack`'s edge volumes (see the module docs; `+∞`
    /// or NaN where the `f32` test does not apply).
    #[inline(always)]
    fn edge_bound(&self, pack: Pack<'_>) -> f32 {
        let [g0, g1, g2, g3] = pack.edge_terms().map(f64::from);
        let [h0, h1, h2, h3] = self.edge;
        let sum = (g0 * h0 + g1 * h1) + (g2 * h2 + g3 * h3);
        (sum * WIDEN + FLOOR) as f32
    }

    /// The bound `B_X` of `pack`'s plane volumes (see the module docs;
    /// `+∞` or NaN where the `f32` test does not apply).
    #[inline(always)]
    fn plane_bound(&self, pack: Pack<'_>) -> f32 {
        let [q0, q1, q2] = pack.plane_terms().map(f64::from);
        let [r, r_error] = self.plane;
        let sum = q0 + (q1 * r + q2 * r_error);
        (sum * WIDEN + FLOOR) as f32
    }
}

/// The lanes of `pack` the segment certainly meets and those the `f32`
/// test leaves uncertain, as bit masks (lanes in use only), on the lanes
/// `s`.
#[inline(always)]
pub(super) fn test<S: Lanes<PACK>>(s: S, pack: Pack<'_>, ray: &LeafRay<S::F>) -> (u32, u32) {
    let used = (1u32 << pack.count) - 1;
    let edge_bound = ray.edge_bound(pack);
    let (e, dn) = edge_volumes(s, pack, ray);
    let (up, down) = (s.splat(edge_bound), s.splat(-edge_bound));
    // Some volume certainly positive and some certainly negative (no
    // volume is NaN where the bound is finite).
    let (hi, lo) = (
        s.max(s.max(e[0], e[1]), e[2]),
        s.min(s.min(e[0], e[1]), e[2]),
    );
    let edge_miss = s.gt(hi, up) & s.lt(lo, down);
    // Most lanes a segment reaches it passes beside: the planes only
    // where some lane is left.
    if edge_miss & used == used {
        return (0, 0);
    }
    let inside = s.gt(lo, up) | s.lt(hi, down);
    let (sp, sx) = plane_volumes(s, pack, ray, dn);
    let plane_bound = ray.plane_bound(pack);
    let (up, down) = (s.splat(plane_bound), s.splat(-plane_bound));
    let (hi, lo) = (s.max(sp, sx), s.min(sp, sx));
    let plane_miss = s.gt(lo, up) | s.lt(hi, down);
    let crosses = s.gt(hi, up) & s.lt(lo, down);
    let hit = inside & crosses;
    (hit & used, !hit & !edge_miss & !plane_miss & used)
}

/// The computed edge volumes `e₀, e₁, e₂` of every lane, and `d · N` (see
/// the module docs).
#[inline(always)]
fn edge_volumes<S: Lanes<PACK>>(s: S, pack: Pack<'_>, ray: &LeafRay<S::F>) -> ([S::F; 3], S::F) {
    let w = cross(s, ray.d, sub(s, load(s, pack, CORNER), ray.p));
    let e_ab = dot(s, load(s, pack, AB), w);
    let e_ca = dot(s, load(s, pack, CA), w);
    let dn = dot(s, ray.d, normal(s, pack));
    ([e_ab, s.sub(s.sub(dn, e_ab), e_ca), e_ca], dn)
}

/// The computed plane volumes `(s_P, s_X)` of every lane, given the
/// computed `d · N` (see the module docs); `a` and `N` computed again, the
/// same bits as for the edges.
#[inline(always)]
fn plane_volumes<S: Lanes<PACK>>(
    s: S,
    pack: Pack<'_>,
    ray: &LeafRay<S::F>,
    dn: S::F,
) -> (S::F, S::F) {
    let sp = dot(s, sub(s, load(s, pack, CORNER), ray.p), normal(s, pack));
    (sp, s.sub(sp, dn))
}

/// The computed normal `N = E′_ca × E′_ab` of every lane.
#[inline(always)]
fn normal<S: Lanes<PACK>>(s: S, pack: Pack<'_>) -> V3s<S> {
    cross(s, load(s, pack, CA), load(s, pack, AB))
}

/// Three vectors of lanes: the axes of one point per lane.
type V3s<S> = [<S as Lanes<PACK>>::F; 3];

// Functions rather than closures throughout: a closure is compiled apart,
// without the caller's target features.

/// Vector `k` ([`CORNER`], [`AB`], [`CA`]) of every lane.
#[inline(always)]
fn load<S: Lanes<PACK>>(s: S, pack: Pack<'_>, k: usize) -> V3s<S> {
    [
        s.load(pack.row(k, 0)),
        s.load(pack.row(k, 1)),
        s.load(pack.row(k, 2)),
    ]
}

#[inline(always)]
fn splat<S: Lanes<PACK>>(s: S, v: [f32; 3]) -> V3s<S> {
    [s.splat(v[0]), s.splat(v[1]), s.splat(v[2])]
}

#[inline(always)]
fn sub<S: Lanes<PACK>>(s: S, u: V3s<S>, v: V3s<S>) -> V3s<S> {
    [s.sub(u[0], v[0]), s.sub(u[1], v[1]), s.sub(u[2], v[2])]
}

/// `u × v`, each component two products and a difference.
#[inline(always)]
fn cross<S: Lanes<PACK>>(s: S, u: V3s<S>, v: V3s<S>) -> V3s<S> {
    [
        s.sub(s.mul(u[1], v[2]), s.mul(u[2], v[1])),
        s.sub(s.mul(u[2], v[0]), s.mul(u[0], v[2])),
        s.sub(s.mul(u[0], v[1]), s.mul(u[1], v[0])),
    ]
}

/// `u · v`, summed left to right.
#[inline(always)]
fn dot<S: Lanes<PACK>>(s: S, u: V3s<S>, v: V3s<S>) -> S::F {
    s.add(
        s.add(s.mul(u[0], v[0]), s.mul(u[1], v[1])),
        s.mul(u[2], v[2]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;
    use crate::bvh::lanes::Portable;
    use crate::kernel::segment::segment_blocked;

    /// The packs holding `triangles` (one pack), occluder indices in order.
    fn packs_of(triangles: &[[DVec3; 3]]) -> Packs {
        let with_ids: Vec<([DVec3; 3], u32)> = triangles
            .iter()
            .enumerate()
            .map(|(i, &t)| (t, i as u32))
            .collect();
        let mut packs = Packs::default();
        packs.push(&with_ids);
        packs.finish();
        packs
    }

    /// What [`test`] says of each lane of `triangles` (one pack) for the
    /// segment `(p, x)`, on the portable lanes and, where the processor
    /// has them, on AVX2's: `(hit, unsure)`. The two forms agree bit for
    /// bit.
    fn verdicts_of(triangles: &[[DVec3; 3]], p: DVec3, x: DVec3) -> (u32, u32) {
        let packs = packs_of(triangles);
        let pack = packs.get(0);
        let portable = test(Portable, pack, &LeafRay::new(Portable, p, x));
        #[cfg(all(feature = "simd", target_arch = "x86_64"))]
        if let Some(v3) = pulp::x86::V3::try_new() {
            let s = crate::bvh::lanes::Avx8(v3);
            let wide = v3.vectorize(
                #[inline(always)]
                || test(s, pack, &LeafRay::new(s, p, x)),
            );
            assert_eq!(wide, portable, "AVX2 and portable lanes differ");
        }
        portable
    }

    /// Where a stiff case's corners lie: a size (`10⁻⁶` to `10⁶`), a centre
    /// (the origin, or up to `10⁹` off on every axis), and whether every
    /// coordinate is rounded to `f32`.
    struct Frame {
        scale: f64,
        centre: f64,
        f32_exact: bool,
    }

    impl Frame {
        /// Draws the size and centre, then `f32_exact` (which may draw).
        fn new(rng: &mut Rng, f32_exact: impl FnOnce(&mut Rng) -> bool) -> Frame {
            let scale = rng.log_uniform(-6.0, 6.0);
            let centre = if rng.chance(0.5) {
                0.0
            } else {
                rng.log_uniform(0.0, 9.0) * rng.sign()
            };
            let f32_exact = f32_exact(rng);
            Frame {
                scale,
                centre,
                f32_exact,
            }
        }

        /// `v`, rounded to `f32` where the frame is.
        fn round(&self, v: DVec3) -> DVec3 {
            if self.f32_exact {
                v.as_vec3().as_dvec3()
            } else {
                v
            }
        }

        /// A corner: each coordinate the centre plus a non-dyadic offset
        /// of the frame's size, now and then exactly the centre.
        fn corner(&self, rng: &mut Rng) -> DVec3 {
            let mut coordinate = || {
                if rng.chance(0.05) {
                    self.centre
                } else {
                    self.centre + rng.uniform(-1.0, 1.0) * self.scale
                }
            };
            self.round(DVec3::new(coordinate(), coordinate(), coordinate()))
        }
    }

    /// The segments of the stiff cases against `t`: through a corner, an
    /// edge's point, the inside, or anywhere; from or to a point of the
    /// triangle's plane (exactly as rounded, or a few ulps off); in the
    /// plane; short of it.
    fn segment(rng: &mut Rng, t: &[DVec3; 3], scale: f64) -> (DVec3, DVec3) {
        let point = |rng: &mut Rng| {
            let (u, v) = (rng.uniform(-0.2, 1.2), rng.uniform(-0.2, 1.2));
            t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v
        };
        let aim = match rng.below(5) {
            0 => t[rng.below(3) as usize],
            1 => {
                let k = rng.below(3) as usize;
                t[k] + (t[(k + 1) % 3] - t[k]) * rng.uniform(0.0, 1.0)
            }
            2 => (t[0] + t[1] + t[2]) / 3.0,
            _ => point(rng),
        };
        let away = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ) * scale
            * 3.0;
        let ulps = |v: f64, n: i64| f64::from_bits((v.to_bits() as i64 + n) as u64);
        let nudge = |rng: &mut Rng, q: DVec3| {
            let n = rng.below(7) as i64 - 3;
            DVec3::new(ulps(q.x, n), ulps(q.y, n), ulps(q.z, n))
        };
        match rng.below(6) {
            // From a point of the plane (or a few ulps off it).
            0 => {
                let q = point(rng);
                (nudge(rng, q), aim + away)
            }
            // To a point of the plane.
            1 => {
                let q = point(rng);
                (aim + away, nudge(rng, q))
            }
            // In the plane.
            2 => (point(rng), point(rng)),
            // Stopping short of the aim.
            3 => (aim + away, aim + away * 0.5),
            // Through the aim.
            _ => (aim + away, aim - away * rng.uniform(0.1, 2.0)),
        }
    }

    /// Certain verdicts are the exact test's, on segments grazing edges
    /// and corners, through points of edges shared by two triangles,
    /// from, to and in a triangle's plane, and short of it; on triangles
    /// of every size at offsets up to `10⁹`, with and without `f32`
    /// corners and endpoints, some degenerate; uncertain lanes occur (the
    /// exact test is exercised) and so do certain hits and misses.
    #[test]
    fn certain_verdicts_are_the_exact_tests() {
        let mut rng = Rng::new(47);
        let mut tally = [0usize; 3];
        for case in 0..20_000 {
            let frame = Frame::new(&mut rng, |_| case % 3 == 0);
            let (scale, f32_exact) = (frame.scale, frame.f32_exact);
            let round = |v: DVec3| frame.round(v);
            let corner = |rng: &mut Rng| frame.corner(rng);
            let first = [corner(&mut rng), corner(&mut rng), corner(&mut rng)];
            let count = 1 + rng.below(PACK as u64) as usize;
            let mut triangles = vec![first];
            while triangles.len() < count {
                let k = rng.below(3) as usize;
                let (a, b) = (first[k], first[(k + 1) % 3]);
                // A neighbour across an edge, a degenerate one, or another.
                triangles.push(match rng.below(4) {
                    0 => [b, a, corner(&mut rng)],
                    1 => [a, b, round(a + (b - a) * 0.5)],
                    _ => [corner(&mut rng), corner(&mut rng), corner(&mut rng)],
                });
            }
            let target = triangles[rng.below(count as u64) as usize];
            let (p, x) = segment(&mut rng, &target, scale);
            let (p, x) = if f32_exact || rng.chance(0.5) {
                (round(p), round(x))
            } else {
                (p, x)
            };
            let (hit, unsure) = verdicts_of(&triangles, p, x);
            for (lane, t) in triangles.iter().enumerate() {
                let exact = segment_blocked(p, x, t);
                if unsure >> lane & 1 == 1 {
                    tally[2] += 1;
                } else {
                    assert_eq!(
                        hit >> lane & 1 == 1,
                        exact,
                        "case {case} lane {lane}: {t:?} {p:?} {x:?}"
                    );
                    tally[usize::from(exact)] += 1;
                }
            }
            assert_eq!((hit | unsure) >> count, 0, "lanes beyond the count");
        }
        assert!(tally.iter().all(|&n| n > 1000), "{tally:?}");
    }

    /// The bounds hold: on the stiff cases of
    /// `certain_verdicts_are_the_exact_tests`, every computed volume is
    /// within its bound of the exact determinant (evaluated by
    /// `orient3d_value`, relative error `2⁻⁴⁰`). Reports how close the
    /// errors come.
    #[test]
    fn computed_volumes_are_within_their_bounds() {
        use crate::kernel::predicate::orient3d_value;
        let mut rng = Rng::new(59);
        let mut closest = 0.0f64;
        for _ in 0..20_000 {
            let frame = Frame::new(&mut rng, |rng| rng.chance(0.3));
            let scale = frame.scale;
            let round = |v: DVec3| frame.round(v);
            let corner = |rng: &mut Rng| frame.corner(rng);
            let triangles: Vec<[DVec3; 3]> = (0..PACK)
                .map(|_| [corner(&mut rng), corner(&mut rng), corner(&mut rng)])
                .collect();
            let target = triangles[rng.below(PACK as u64) as usize];
            let (p, x) = segment(&mut rng, &target, scale);
            let (p, x) = if rng.chance(0.5) {
                (round(p), round(x))
            } else {
                (p, x)
            };
            let packs = packs_of(&triangles);
            let pack = packs.get(0);
            let ray = LeafRay::new(Portable, p, x);
            let (edge_bound, plane_bound) = (ray.edge_bound(pack), ray.plane_bound(pack));
            if !(edge_bound.is_finite() && plane_bound.is_finite()) {
                continue;
            }
            let (e, dn) = edge_volumes(Portable, pack, &ray);
            let (sp, sx) = plane_volumes(Portable, pack, &ray, dn);
            for (lane, t) in triangles.iter().enumerate() {
                let [ta, tb, tc] = *t;
                let exact = [
                    (e[0][lane], orient3d_value(x, ta, tb, p), edge_bound),
                    (e[1][lane], orient3d_value(x, tb, tc, p), edge_bound),
                    (e[2][lane], orient3d_value(x, tc, ta, p), edge_bound),
                    (sp[lane], orient3d_value(ta, tb, tc, p), plane_bound),
                    (sx[lane], orient3d_value(ta, tb, tc, x), plane_bound),
                ];
                for (k, (computed, value, bound)) in exact.into_iter().enumerate() {
                    let error = (f64::from(computed) - value).abs() - value.abs() * 1e-12;
                    assert!(
                        error <= f64::from(bound),
                        "volume {k}, lane {lane}: {computed} against {value} (bound {bound}): {t:?} {p:?} {x:?}"
                    );
                    closest = closest.max(error / f64::from(bound));
                }
            }
        }
        eprintln!("largest error / bound: {closest:.3e}");
        assert!(
            closest > 1e-2,
            "the cases come near their bounds: {closest:e}"
        );
    }

    /// On ordinary segments — triangles of a soup, segments from a floor to
    /// a light far from every corner, edge and plane — the `f32` test
    /// decides almost every lane (the exact test is the exception).
    #[test]
    fn ordinary_segments_are_decided_in_f32() {
        let mut rng = Rng::new(53);
        let (mut lanes, mut unsure_lanes) = (0u32, 0u32);
        for _ in 0..20_000 {
            let centre = DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(0.1, 0.9),
            );
            let triangles: Vec<[DVec3; 3]> = (0..PACK)
                .map(|_| {
                    let c = centre
                        + DVec3::new(
                            rng.uniform(-0.05, 0.05),
                            rng.uniform(-0.05, 0.05),
                            rng.uniform(-0.05, 0.05),
                        );
                    [0, 1, 2].map(|_| {
                        c + DVec3::new(
                            rng.uniform(-0.01, 0.01),
                            rng.uniform(-0.01, 0.01),
                            rng.uniform(-0.01, 0.01),
                        )
                    })
                })
                .collect();
            let p = DVec3::new(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), -0.5);
            let x = DVec3::new(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1.5);
            let (_, unsure) = verdicts_of(&triangles, p, x);
            lanes += PACK as u32;
            unsure_lanes += unsure.count_ones();
        }
        assert!(
            unsure_lanes * 10_000 < lanes,
            "{unsure_lanes} of {lanes} uncertain"
        );
    }
}
