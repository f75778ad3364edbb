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
//! `a = A − P`, `b = B − P`, `c = C − P` and the edges `E_ab = B − A`,
//! `E_bc = C − B`, `E_ca = A − C`, the same determinants are
//!
//! - `e₀ = d · (a × E_ab)`, `e₁ = d · (b × E_bc)`, `e₂ = d · (c × E_ca)`
//!   (`d = X − P`; `a × b = a × (b − a)`),
//! - `s_P = a · N`, `s_X = (A − X) · N`, `N = E_ca × E_ab`,
//!
//! products of a difference from an endpoint and of edges, whose errors
//! scale with the triangle's size rather than with its distance (the
//! forms of [`segment_blocked`] multiply two distances).
//!
//! # The bound
//!
//! Let `u = 2⁻²⁴`. The stored corners are the triangle's rounded to
//! nearest `f32`, `A′ = A + O(ε_c)` (`ε_c` the pack's largest rounding,
//! `0` for corners that are `f32` values); the ray's are `P′ = fl₃₂(P)`,
//! `X′ = fl₃₂(X)`, `d′ = fl₃₂(fl₆₄(X − P))`, with `ε_r` bounding `|P −
//! P′|∞` and `|X − X′|∞` and `ε_d` bounding `|d′ − (X − P)|∞` (all
//! computed exactly in `f64` and rounded up). The test computes, in `f32`,
//! `a = fl(A′ − P′)` (and `b`, `c`, `A′ − X′` alike), `E = fl(B′ − A′)`
//! (and the other edges), then each determinant as a cross product and a
//! dot product. With `M` the pack's largest corner magnitude, `R =
//! max(|P′|∞, |X′|∞)`, `S = M + R` and `L` the pack's largest edge
//! `|B′ − A′|∞`:
//!
//! - `Â = S (1 + u) + ε_c + ε_r` bounds both the computed `|a|∞` and the
//!   true `|A − P|∞` (and `A − X`'s), and `ε_a = u S + ε_c + ε_r` their
//!   difference (one rounding of a difference of stored values, plus the
//!   roundings of the corner and the endpoint);
//! - `Ê = L (1 + u) + 2 ε_c` bounds the computed and the true edge, `ε_E =
//!   u L + 2 ε_c` their difference;
//! - `D̂ = |d′|∞ + ε_d` bounds the computed and the true `d`.
//!
//! A determinant `det[r₁; r₂; r₃] = r₁ · (r₂ × r₃)` is a sum of six terms
//! each at most `|r₁|∞ |r₂|∞ |r₃|∞`. Evaluated as written (the cross
//! product's components with two products and a difference, then three
//! products and two sums) each term carries at most five roundings, so
//! the computed value is within `6 γ₅ |r₁| |r₂| |r₃|` of the determinant
//! of the computed rows (`γ₅ = 5u/(1 − 5u)`, Higham §3.1). The computed
//! rows differ from the true ones by `δ₁, δ₂, δ₃`, and by
//! multilinearity `det[r₁ + δ₁; …] − det[r₁; …]` telescopes into three
//! determinants each with one row a `δ`: at most `6 (δ₁ r̂₂ r̂₃ + r̂₁ δ₂ r̂₃ +
//! r̂₁ r̂₂ δ₃)` with each `r̂` bounding both the computed and the true row.
//! So the computed edge volumes are within
//!
//! `B_e = 6 (γ₅ D̂ Â Ê + ε_d Â Ê + D̂ ε_a Ê + D̂ Â ε_E) + F`
//!
//! of the exact ones, and both plane volumes within
//!
//! `B_s = 6 (γ₅ Â Ê² + ε_a Ê² + 2 Â Ê ε_E) + F`.
//!
//! `F = 2⁻¹⁰⁰` covers underflow: the test runs only where `M` and `R` are
//! at most `2⁴⁰` (elsewhere every lane goes to the exact test), so every
//! row is below `2⁴²` in magnitude, no value overflows, and the absolute
//! error of the products that underflow (at most `2⁻¹⁵⁰` each, carried
//! through by factors below `2⁴²`) stays below `2⁻¹⁰⁴`.
//!
//! # Evaluating the bounds
//!
//! `Â` and `ε_a` are sums of a pack's part and a segment's: `Â = m + r`,
//! `ε_a = m′ + r′` with `m = M (1 + u) + ε_c`, `m′ = u M + ε_c`, `r = R (1 +
//! u) + ε_r`, `r′ = u R + ε_r`. Multiplied out, with `k_e = 6 (γ₅ D̂ +
//! ε_d)` and `k_l = 6 D̂`,
//!
//! `B_e − F = k_e (Ê m) + k_l (Ê m′ + ε_E m) + (k_e r + k_l r′) Ê + (k_l r) ε_E`,
//!
//! `B_s − F = (m Q₁ + m′ Q₂) + r Q₁ + r′ Q₂`, `Q₁ = 6 γ₅ Ê² + 12 Ê ε_E`, `Q₂ = 6 Ê²`:
//!
//! each a short sum of products of a pack's terms (computed once, at the
//! build: `Ê m`, `Ê m′ + ε_E m`, `Ê`, `ε_E`, and `m Q₁ + m′ Q₂`, `Q₁`, `Q₂`)
//! and a segment's (computed once a segment). Every term is nonnegative;
//! each is computed in `f64` from exact inputs (a few roundings of
//! `2⁻⁵³`), widened by `2⁻²²` and rounded up to `f32` (a pack's) or kept
//! in `f64` (a segment's), and the sums, computed in `f64` (three
//! roundings), are widened by `2⁻²²` again before they are rounded to
//! `f32`: the bounds used are at least `B_e` and `B_s`. A pack whose `M`
//! exceeds `2⁴⁰` stores `+∞` for the terms with `m` in them, a segment
//! whose `R` does for `r` and `r′`: its bounds are then `+∞` or NaN (a
//! product `0 · ∞`), and no computed volume compares certain against
//! either (the comparisons are ordered), so every lane is uncertain.
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
//! how many lanes are evaluated at once or on the instructions used
//! (`tests::lanes_decide_as_one_triangle_at_a_time`).
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
/// `F`: the bound's floor, covering underflow.
const FLOOR: f64 = 1.0 / (1u128 << 100) as f64;
/// The largest corner and endpoint magnitude the `f32` test takes, `2⁴⁰`.
const REACH: f64 = (1u64 << 40) as f64;
/// The widening of a bound computed in `f64` before rounding it to `f32`.
const WIDEN: f64 = 1.0 + 1.0 / (1u32 << 22) as f64;

/// Floats of a pack's header: the lane count less one (bits), the
/// edge bound's terms `Ê m`, `Ê m′ + ε_E m`, `Ê`, `ε_E` and the plane
/// bound's `m Q₁ + m′ Q₂`, `Q₁`, `Q₂` (see the module docs).
const HEADER: usize = 8;
/// The floats read from a pack's start, at most: the header, nine rows of
/// [`PACK`] lanes each read [`PACK`] floats on, and the occluder indices
/// after them.
const SPAN: usize = HEADER + 9 * PACK + PACK;

/// The leaves' packs, one after another in one array of `f32`, each on a
/// multiple of eight floats (32 bytes): a header of [`HEADER`] floats,
/// then its triangles' corners rounded to nearest `f32`, row by row
/// (corner `k`, axis `a`: row `3k + a`), each row `count` floats long (a
/// lane a triangle), then the triangles' occluder indices (their bits).
/// A row is read as [`PACK`] floats, the lanes beyond `count` being
/// whatever follows (masked off: their verdicts are not used); the array
/// ends with [`SPAN`] floats of padding, so every read stays within it. A
/// pack of `n` triangles takes `32 + 40 n` bytes, rounded up to 32.
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

impl Packs {
    /// Appends the pack of `triangles` (1 to [`PACK`] of them, finite,
    /// each with its occluder index); returns its index (its start in
    /// units of eight floats). Call [`Packs::finish`] after the last.
    pub(super) fn push(&mut self, triangles: &[([DVec3; 3], u32)]) -> u32 {
        let count = triangles.len();
        assert!((1..=PACK).contains(&count));
        let start = self.data.len();
        assert_eq!(start % 8, 0);
        let (mut m, mut c, mut l) = (0.0f64, 0.0f64, 0.0f64);
        let mut rows = [[0.0f32; PACK]; 9];
        for (lane, &(t, _)) in triangles.iter().enumerate() {
            let stored = t.map(|v| v.as_vec3().as_dvec3());
            for k in 0..3 {
                for axis in 0..3 {
                    rows[3 * k + axis][lane] = stored[k][axis] as f32;
                }
                // Exact in `f64`: a value less its nearest `f32`, and a
                // difference of two `f32` values.
                m = m.max(stored[k].abs().max_element());
                c = c.max((t[k] - stored[k]).abs().max_element());
                l = l.max((stored[(k + 1) % 3] - stored[k]).abs().max_element());
            }
        }
        self.data.push(f32::from_bits(count as u32 - 1));
        self.data.extend(pack_terms(m, c, l));
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

/// A pack's terms of the bounds as stored (see the module docs): `Ê m`,
/// `Ê m′ + ε_E m`, `Ê`, `ε_E`, then `m Q₁ + m′ Q₂`, `Q₁`, `Q₂`, each
/// computed in `f64` from `M` (the largest stored corner magnitude), `ε_c`
/// (the largest rounding of a corner) and `L` (the largest stored edge),
/// all three exact, then widened and rounded up to `f32`; the first of
/// each list `+∞` when `M` is beyond [`REACH`].
fn pack_terms(magnitude: f64, corner_error: f64, edge: f64) -> [f32; 7] {
    let (c, l) = (corner_error, edge);
    let m = magnitude * (1.0 + U) + c;
    let m_error = magnitude * U + c;
    let e = l * (1.0 + U) + 2.0 * c;
    let e_error = l * U + 2.0 * c;
    let q1 = 6.0 * GAMMA5 * e * e + 12.0 * e * e_error;
    let q2 = 6.0 * e * e;
    // All of them far below `f32::MAX` within reach (`M, L ≤ 2⁴¹`), where
    // `f32_up` rounds up.
    let up = |t: f64| f32_up(t * WIDEN);
    let reach = |t: f32| if magnitude <= REACH { t } else { f32::INFINITY };
    [
        reach(up(e * m)),
        up(e * m_error + e_error * m),
        up(e),
        up(e_error),
        reach(up(m * q1 + m_error * q2)),
        up(q1),
        up(q2),
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

    /// Corner `k`'s axis `axis`, lane by lane (lanes from `count` on are
    /// whatever follows).
    #[inline(always)]
    fn row(&self, k: usize, axis: usize) -> &'a [f32; PACK] {
        let at = HEADER + (3 * k + axis) * self.count;
        self.data[at..at + PACK]
            .try_into()
            .expect("within the span")
    }

    /// The edge bound's terms (`Ê m`, `Ê m′ + ε_E m`, `Ê`, `ε_E`).
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
    /// Corner `k` of lane `lane`'s triangle as stored.
    pub(super) fn corner(&self, k: usize, lane: usize) -> DVec3 {
        DVec3::from_array([0, 1, 2].map(|a| f64::from(self.row(k, a)[lane])))
    }

    /// Its occluder indices, lane by lane.
    pub(super) fn ids(&self) -> Vec<u32> {
        (0..self.count).map(|lane| self.id(lane)).collect()
    }

    /// Checks the bounds' terms against the pack's triangles (its indices
    /// into `triangles`): with `M`, `ε_c` and `L` found here from the
    /// triangles and their stored corners, each stored term is at least
    /// the module docs' definition and at most `2⁻²⁰` above it (`+∞`, the
    /// terms with `m`, where `M` is beyond reach).
    pub(super) fn check_terms(&self, triangles: &[[DVec3; 3]]) {
        let (mut magnitude, mut c, mut l) = (0.0f64, 0.0f64, 0.0f64);
        for lane in 0..self.count {
            let t = triangles[self.id(lane) as usize];
            let stored: [DVec3; 3] = core::array::from_fn(|k| self.corner(k, lane));
            for k in 0..3 {
                magnitude = magnitude.max(stored[k].abs().max_element());
                c = c.max((t[k] - stored[k]).abs().max_element());
                l = l.max((stored[(k + 1) % 3] - stored[k]).abs().max_element());
            }
        }
        let (m, m_error) = (magnitude * (1.0 + U) + c, magnitude * U + c);
        let (e, e_error) = (l * (1.0 + U) + 2.0 * c, l * U + 2.0 * c);
        let (q1, q2) = (6.0 * GAMMA5 * e * e + 12.0 * e * e_error, 6.0 * e * e);
        let defined = [
            e * m,
            e * m_error + e_error * m,
            e,
            e_error,
            m * q1 + m_error * q2,
            q1,
            q2,
        ];
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
/// (on its first leaf): the endpoints and direction in `f32`, each axis in
/// every lane, and the segment's terms of the bounds.
pub(super) struct LeafRay<F> {
    p: [F; 3],
    x: [F; 3],
    d: [F; 3],
    /// The segment's terms of the bounds (see [`Terms`]).
    edge: [f64; 4],
    plane: [f64; 2],
}

/// The scalars of a [`LeafRay`].
struct Terms {
    p: [f32; 3],
    x: [f32; 3],
    d: [f32; 3],
    /// `k_e`, `k_l`, `k_e r + k_l r′`, `k_l r`: the edge bound's factors of
    /// a pack's `Ê m`, `Ê m′ + ε_E m`, `Ê`, `ε_E` (see the module docs).
    edge: [f64; 4],
    /// `r`, `r′`: the plane bound's factors of a pack's `Q₁`, `Q₂`; `+∞`
    /// where `R` is beyond [`REACH`].
    plane: [f64; 2],
}

/// The scalars of the segment `(p, x)` for [`LeafRay::new`]: out of line,
/// so that they are computed only for segments that reach a leaf (inline,
/// the compiler computed them ahead of the walk for every segment).
#[inline(never)]
fn terms(p: DVec3, x: DVec3) -> Terms {
    let d = x - p;
    let (p32, x32, d32) = (p.as_vec3(), x.as_vec3(), d.as_vec3());
    // Each difference exact in `f64`.
    let end_error = (p - p32.as_dvec3())
        .abs()
        .max((x - x32.as_dvec3()).abs())
        .max_element();
    let length_error =
        ((d - d32.as_dvec3()).abs() + d.abs() * (2.0 * f64::EPSILON)).max_element() * WIDEN;
    let length = f64::from(d32.abs().max_element()) + length_error;
    let reach = f64::from(p32.abs().max(x32.abs()).max_element());
    let end_error = end_error * WIDEN;
    let (r, r_error) = if reach <= REACH {
        (reach * (1.0 + U) + end_error, reach * U + end_error)
    } else {
        (f64::INFINITY, f64::INFINITY)
    };
    let (k_edge, k_length) = (6.0 * (GAMMA5 * length + length_error), 6.0 * length);
    Terms {
        p: p32.to_array(),
        x: x32.to_array(),
        d: d32.to_array(),
        edge: [
            k_edge,
            k_length,
            k_edge * r + k_length * r_error,
            k_length * r,
        ],
        plane: [r, r_error],
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
            x: splat(s, t.x),
            d: splat(s, t.d),
            edge: t.edge,
            plane: t.plane,
        }
    }

    /// The bound `B_e` of `pack`'s edge volumes (see the module docs; `+∞`
    /// or NaN where the `f32` test does not apply).
    #[inline(always)]
    fn edge_bound(&self, pack: Pack<'_>) -> f32 {
        let [g0, g1, g2, g3] = pack.edge_terms().map(f64::from);
        let [h0, h1, h2, h3] = self.edge;
        let sum = (g0 * h0 + g1 * h1) + (g2 * h2 + g3 * h3);
        (sum * WIDEN + FLOOR) as f32
    }

    /// The bound `B_s` of `pack`'s plane volumes (see the module docs;
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
    let e = edge_volumes(s, pack, ray);
    let (up, down) = (s.splat(edge_bound), s.splat(-edge_bound));
    let pos = [s.gt(e[0], up), s.gt(e[1], up), s.gt(e[2], up)];
    let neg = [s.lt(e[0], down), s.lt(e[1], down), s.lt(e[2], down)];
    let edge_miss = (pos[0] | pos[1] | pos[2]) & (neg[0] | neg[1] | neg[2]);
    // Most lanes a segment reaches it passes beside: the planes only
    // where some lane is left.
    if edge_miss & used == used {
        return (0, 0);
    }
    let inside = (pos[0] & pos[1] & pos[2]) | (neg[0] & neg[1] & neg[2]);
    let (sp, sx) = plane_volumes(s, pack, ray);
    let plane_bound = ray.plane_bound(pack);
    let (up, down) = (s.splat(plane_bound), s.splat(-plane_bound));
    let (p_pos, p_neg) = (s.gt(sp, up), s.lt(sp, down));
    let (x_pos, x_neg) = (s.gt(sx, up), s.lt(sx, down));
    let plane_miss = (p_pos & x_pos) | (p_neg & x_neg);
    let crosses = (p_pos & x_neg) | (p_neg & x_pos);
    let hit = inside & crosses;
    (hit & used, !hit & !edge_miss & !plane_miss & used)
}

/// The computed edge volumes `e₀, e₁, e₂` of every lane (see the module
/// docs). Edge by edge, each reading its corners from the pack again (a
/// load from the first-level cache is cheaper than the registers the
/// three corners at once would spill).
#[inline(always)]
fn edge_volumes<S: Lanes<PACK>>(s: S, pack: Pack<'_>, ray: &LeafRay<S::F>) -> [S::F; 3] {
    [
        edge_volume(s, pack, ray, 0, 1),
        edge_volume(s, pack, ray, 1, 2),
        edge_volume(s, pack, ray, 2, 0),
    ]
}

/// `d · ((U′ − P′) × (V′ − U′))` for the corners `U = k`, `V = l`.
#[inline(always)]
fn edge_volume<S: Lanes<PACK>>(
    s: S,
    pack: Pack<'_>,
    ray: &LeafRay<S::F>,
    k: usize,
    l: usize,
) -> S::F {
    let (u, v) = (load(s, pack, k), load(s, pack, l));
    dot(s, ray.d, cross(s, sub(s, u, ray.p), sub(s, v, u)))
}

/// The computed plane volumes `(s_P, s_X)` of every lane (see the module
/// docs).
#[inline(always)]
fn plane_volumes<S: Lanes<PACK>>(s: S, pack: Pack<'_>, ray: &LeafRay<S::F>) -> (S::F, S::F) {
    let (a, b, c) = (load(s, pack, 0), load(s, pack, 1), load(s, pack, 2));
    let n = cross(s, sub(s, a, c), sub(s, b, a));
    (dot(s, sub(s, a, ray.p), n), dot(s, sub(s, a, ray.x), n))
}

/// Three vectors of lanes: the axes of one point per lane.
type V3s<S> = [<S as Lanes<PACK>>::F; 3];

// Functions rather than closures throughout: a closure is compiled apart,
// without the caller's target features.

/// Corner `k` of every lane.
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
            let e = edge_volumes(Portable, pack, &ray);
            let (sp, sx) = plane_volumes(Portable, pack, &ray);
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
