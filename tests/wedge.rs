//! Properties of `kernel::wedge`:
//! the wedge and the penumbra quad never miss a partially occluded receiver,
//! checked against an independent partial-occlusion test evaluated in
//! 256-bit arithmetic; their tightness (wedge volume and quad area against
//! the true region, sampled); `f32` against `f64`; typed errors and no panic
//! on arbitrary bit patterns.
//!
//! `SOFTSHADOW_PRINT_ACCURACY=1 cargo test --test wedge -- --nocapture`
//! prints the accuracy rows; `SOFTSHADOW_EXHAUSTIVE=1` multiplies the sample
//! counts by 50.

mod support;
use support::{printing, samples, Big};

use proptest::prelude::*;
use softshadow::arbitrary::mesh::{
    light_frame_edge, sphere_light, unit_vector, wedge_case, WedgeCase,
};
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3, Vec3};
use softshadow::kernel::catalogue;
use softshadow::kernel::wedge::{f32 as w32, f64 as w64, WedgeError};

/// Budgets of the `f32` wedge against the `f64` one on the same input, in
/// units of the `f32` ε (the kernel catalogue's): the angle between their
/// planes, the relative difference of their quad radii.
const BUDGET_NORMAL_F32: f64 = catalogue::wedge::NORMAL_F32.bound;
const BUDGET_QUAD_RADIUS_F32: f64 = catalogue::wedge::QUAD_RADIUS_F32.bound;

// ---------------------------------------------------------------------------
// The independent partial-occlusion test.

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Occlusion {
    /// The edge meets the open segment from `p` to an interior point of the
    /// facing disk.
    Affected,
    /// It does not.
    Clear,
    /// `p` inside the light, or the answer within 2⁻²⁰⁰ of the decision.
    Undecided,
}

struct BigVec([Big; 3]);

impl BigVec {
    fn new(v: DVec3) -> BigVec {
        BigVec([Big::new(v.x), Big::new(v.y), Big::new(v.z)])
    }
    fn sub(&self, o: &BigVec) -> BigVec {
        BigVec([0, 1, 2].map(|i| self.0[i].sub(&o.0[i])))
    }
    fn dot(&self, o: &BigVec) -> Big {
        self.0[0]
            .mul(&o.0[0])
            .add(&self.0[1].mul(&o.0[1]))
            .add(&self.0[2].mul(&o.0[2]))
    }
}

fn big_abs(x: &Big) -> Big {
    if x.is_negative() {
        x.neg()
    } else {
        x.clone()
    }
}

/// Visibility (docs/definitions.md): `p` is affected by the edge when the edge meets the open
/// segment from `p` to a point of the facing disk (centre `c`, radius `r`,
/// normal along `c − p`). With `ν = c − p`, `H² = ν·ν`, `rel(λ) = e0 + λ(e1 −
/// e0) − p` and `s = rel·ν` (depth times `H`), the edge point projects from
/// `p` into the open disk and lies strictly between `p` and the disk's plane
/// exactly when `0 < s < H²` and
///
/// `G(λ) = (|rel|² H² − s²) H² − r² s² < 0`
///
/// (the squared lateral distance, scaled to the disk's plane, below `r²`).
/// `G` is a quadratic in `λ`; its minimum over the feasible `λ`-interval is
/// evaluated at the interval ends and the vertex in 256-bit arithmetic. No
/// geometry is shared with the crate (no planes, no tangents, no
/// projection onto the image plane).
fn occlusion(p: DVec3, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> Occlusion {
    let (p, e0b, e1b, cb) = (
        BigVec::new(p),
        BigVec::new(e0),
        BigVec::new(e1),
        BigVec::new(c),
    );
    let nu = cb.sub(&p);
    let h2 = nu.dot(&nu);
    let r2 = Big::new(r).mul(&Big::new(r));
    if !r2.lt(&h2) {
        return Occlusion::Undecided;
    }
    let rel0 = e0b.sub(&p);
    let delta = e1b.sub(&e0b);
    let (s0, s1) = (rel0.dot(&nu), delta.dot(&nu));
    let (a2, a1, a0) = (
        delta.dot(&delta),
        rel0.dot(&delta).mul(&Big::new(2.0)),
        rel0.dot(&rel0),
    );
    let two = Big::new(2.0);
    // G = A λ² + B λ + C.
    let ga = a2
        .mul(&h2)
        .sub(&s1.mul(&s1))
        .mul(&h2)
        .sub(&r2.mul(&s1.mul(&s1)));
    let gb = a1
        .mul(&h2)
        .sub(&two.mul(&s0).mul(&s1))
        .mul(&h2)
        .sub(&r2.mul(&two).mul(&s0).mul(&s1));
    let gc = a0
        .mul(&h2)
        .sub(&s0.mul(&s0))
        .mul(&h2)
        .sub(&r2.mul(&s0.mul(&s0)));
    // The λ-interval where 0 < s < H², within [0, 1].
    let (mut lo, mut hi) = (Big::zero(), Big::new(1.0));
    if s1.is_zero() {
        if !(s0.is_positive() && s0.lt(&h2)) {
            return Occlusion::Clear;
        }
    } else {
        let at_zero = s0.neg().div(&s1);
        let at_h2 = h2.sub(&s0).div(&s1);
        let (a, b) = if s1.is_positive() {
            (at_zero, at_h2)
        } else {
            (at_h2, at_zero)
        };
        if lo.lt(&a) {
            lo = a;
        }
        if b.lt(&hi) {
            hi = b;
        }
        if !lo.lt(&hi) {
            return Occlusion::Clear;
        }
    }
    let g = |l: &Big| ga.mul(l).add(&gb).mul(l).add(&gc);
    let mut min = g(&lo);
    let g_hi = g(&hi);
    if g_hi.lt(&min) {
        min = g_hi;
    }
    if ga.is_positive() {
        let vertex = gb.neg().div(&ga.mul(&two));
        if lo.lt(&vertex) && vertex.lt(&hi) {
            let g_v = g(&vertex);
            if g_v.lt(&min) {
                min = g_v;
            }
        }
    }
    let scale = big_abs(&ga).add(&big_abs(&gb)).add(&big_abs(&gc));
    let band = scale.mul(&Big::new(2f64.powi(-200)));
    if min.lt(&band.neg()) {
        Occlusion::Affected
    } else if band.lt(&min) {
        Occlusion::Clear
    } else {
        Occlusion::Undecided
    }
}

/// A receiver in the region the edge may affect, built from its definition:
/// `p = q + t (q − y)` with `q` on the edge and `y` in the light (on the
/// sphere, in the ball, or on the disk facing `q`), `t` log-uniform; about
/// half of them are affected (the rest lie in the thin shell between the
/// ball's and the facing disk's cones), many within rounding of `W`'s
/// boundary, which is also the wedge's.
fn constructive_receiver(rng: &mut Rng, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> DVec3 {
    let q = e0 + rng.unit() * (e1 - e0);
    let y = match rng.below(3) {
        0 => c + r * unit_vector(rng),
        1 => c + r * rng.unit().cbrt() * unit_vector(rng),
        _ => {
            let axis = (c - q).normalize_or(DVec3::Z);
            let (u, v) = axis.any_orthonormal_pair();
            let a = rng.uniform(0.0, 2.0 * core::f64::consts::PI);
            c + r * rng.unit().sqrt() * (a.cos() * u + a.sin() * v)
        }
    };
    q + rng.log_uniform(-4.0, 2.0) * (q - y)
}

/// A receiver uniform in the ball around the edge's midpoint that holds the
/// edge and the light, twice enlarged.
fn uniform_receiver(rng: &mut Rng, e0: DVec3, e1: DVec3, c: DVec3, r: f64) -> DVec3 {
    let mid = 0.5 * (e0 + e1);
    let extent = 2.0 * ((e1 - e0).length() + (mid - c).length() + r);
    mid + extent * rng.unit().cbrt() * unit_vector(rng)
}

// ---------------------------------------------------------------------------
// The wedge.

/// Counts for one precision.
#[derive(Default)]
struct WedgeStats {
    affected: usize,
    missed: usize,
    undecided: usize,
    dropped_planes: usize,
    wedges: usize,
}

fn check_wedge_case(
    case: &WedgeCase,
    rng: &mut Rng,
    receivers: usize,
    f32_too: bool,
) -> [WedgeStats; 2] {
    let mut stats = [WedgeStats::default(), WedgeStats::default()];
    let c = case.light.center;
    let r = case.light.radius;
    if let Ok(wedge) = w64::PenumbraWedge::new(case.e0, case.e1, c, r) {
        stats[0].wedges += 1;
        stats[0].dropped_planes += 4 - wedge.planes().count();
        for k in 0..receivers {
            let p = if k % 2 == 0 {
                constructive_receiver(rng, case.e0, case.e1, c, r)
            } else {
                uniform_receiver(rng, case.e0, case.e1, c, r)
            };
            match occlusion(p, case.e0, case.e1, c, r) {
                Occlusion::Affected => {
                    stats[0].affected += 1;
                    if !wedge.contains(p) {
                        stats[0].missed += 1;
                        eprintln!("f64 miss: {case:?}, p = {p:?}");
                    }
                }
                Occlusion::Undecided => stats[0].undecided += 1,
                Occlusion::Clear => {}
            }
        }
    }
    if f32_too {
        let (e0, e1, c32, r32) = (case.e0.as_vec3(), case.e1.as_vec3(), c.as_vec3(), r as f32);
        if let Ok(wedge) = w32::PenumbraWedge::new(e0, e1, c32, r32) {
            let (e0d, e1d, cd, rd) = (
                DVec3::from(e0),
                DVec3::from(e1),
                DVec3::from(c32),
                f64::from(r32),
            );
            stats[1].wedges += 1;
            stats[1].dropped_planes += 4 - wedge.planes().count();
            for k in 0..receivers {
                let p = if k % 2 == 0 {
                    constructive_receiver(rng, e0d, e1d, cd, rd)
                } else {
                    uniform_receiver(rng, e0d, e1d, cd, rd)
                };
                let p = p.as_vec3();
                if !p.is_finite() {
                    continue;
                }
                match occlusion(DVec3::from(p), e0d, e1d, cd, rd) {
                    Occlusion::Affected => {
                        stats[1].affected += 1;
                        if !wedge.contains(p) {
                            stats[1].missed += 1;
                            eprintln!("f32 miss: {case:?}, p = {p:?}");
                        }
                    }
                    Occlusion::Undecided => stats[1].undecided += 1,
                    Occlusion::Clear => {}
                }
            }
        }
    }
    stats
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every receiver the independent test finds affected is in the wedge,
    /// for `f64` and `f32` wedges over the stiff `wedge_case` generator
    /// (zero-length, huge, radial, through-the-light-line and
    /// ulps-from-tangent edges).
    #[test]
    fn wedge_never_misses(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let case = wedge_case(&mut rng);
        let [s64, s32] = check_wedge_case(&case, &mut rng, 24, true);
        prop_assert_eq!(s64.missed, 0);
        prop_assert_eq!(s32.missed, 0);
    }

    /// No panic and no NaN on arbitrary bit patterns: `new` returns a typed
    /// error or a wedge with finite planes; `contains` and `penumbra_quad`
    /// answer for anything.
    #[test]
    fn arbitrary_bits(bits in proptest::array::uniform12(any::<u64>())) {
        let f: Vec<f64> = bits.iter().map(|&b| f64::from_bits(b)).collect();
        let v = |i: usize| DVec3::new(f[i], f[i + 1], f[i + 2]);
        if let Ok(w) = w64::PenumbraWedge::new(v(0), v(3), v(6), f[9]) {
            prop_assert!(w.planes().all(|p| p.normal.is_finite() && p.offset.is_finite()));
            let _ = w.contains(v(9));
        }
        if let Ok(w64::QuadBound::Quad(q)) = w64::penumbra_quad(v(0), v(3), f[9], f[10]) {
            prop_assert!(q.corners.iter().all(|c| c.is_finite()) && q.radius.is_finite());
        }
        let g: Vec<f32> = bits.iter().map(|&b| f32::from_bits(b as u32)).collect();
        let u = |i: usize| Vec3::new(g[i], g[i + 1], g[i + 2]);
        if let Ok(w) = w32::PenumbraWedge::new(u(0), u(3), u(6), g[9]) {
            prop_assert!(w.planes().all(|p| p.normal.is_finite() && p.offset.is_finite()));
            let _ = w.contains(u(9));
        }
        if let Ok(w32::QuadBound::Quad(q)) = w32::penumbra_quad(u(0), u(3), g[9], g[10]) {
            prop_assert!(q.corners.iter().all(|c| c.is_finite()) && q.radius.is_finite());
        }
    }
}

#[test]
fn wedge_errors() {
    let c = DVec3::ZERO;
    let e = DVec3::new(0.0, 2.0, 0.0);
    assert_eq!(
        w64::PenumbraWedge::new(e, e, c, 1.0),
        Err(WedgeError::ZeroLengthEdge)
    );
    assert_eq!(
        w64::PenumbraWedge::new(e, -e, c, 1.0),
        Err(WedgeError::EdgeTouchesLight)
    );
    assert_eq!(
        w64::PenumbraWedge::new(e, DVec3::X, c, -1.0),
        Err(WedgeError::NonPositiveRadius)
    );
    assert_eq!(
        w64::PenumbraWedge::new(e, DVec3::X * 3.0, c, f64::INFINITY),
        Err(WedgeError::NonFinite)
    );
    assert_eq!(
        w64::PenumbraWedge::new(DVec3::splat(1e308), DVec3::splat(-1e308), c, 1.0),
        Err(WedgeError::OutOfRange)
    );
    assert_eq!(
        w32::PenumbraWedge::new(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            Vec3::ZERO,
            1.0
        ),
        Err(WedgeError::EdgeTouchesLight)
    );
}

/// Sampled tightness: points uniform in a ball around the configuration;
/// the ratio of those in the wedge to those affected. Over ordinary edges
/// (1–100 radii away, lengths 0.1–10 radii).
fn wedge_tightness(rng: &mut Rng, cases: usize, per_case: usize) -> (f64, f64, usize) {
    let (mut sum, mut worst, mut used) = (0.0, 0.0f64, 0);
    for _ in 0..cases {
        let light = sphere_light(rng);
        let (c, r) = (light.center, light.radius);
        let q = c + r * rng.log_uniform(0.0, 2.0) * (1.0 + 1e-3) * unit_vector(rng);
        let half = 0.5 * r * rng.log_uniform(-1.0, 1.0) * unit_vector(rng);
        let (e0, e1) = (q - half, q + half);
        let Ok(wedge) = w64::PenumbraWedge::new(e0, e1, c, r) else {
            continue;
        };
        // Sample near the edge, where the wedge is thin: a ball around the
        // edge of twice its distance to the light.
        let extent = 2.0 * ((q - c).length() + half.length());
        let (mut inside, mut affected) = (0usize, 0usize);
        for _ in 0..per_case {
            let p = q + extent * rng.unit().cbrt() * unit_vector(rng);
            inside += usize::from(wedge.contains(p));
            affected += usize::from(occlusion(p, e0, e1, c, r) == Occlusion::Affected);
        }
        if affected >= 10 {
            let ratio = inside as f64 / affected as f64;
            sum += ratio;
            worst = worst.max(ratio);
            used += 1;
        }
    }
    (sum / used as f64, worst, used)
}

#[test]
fn wedge_accuracy_rows() {
    let mut rng = Rng::new(0x3ed9e);
    let cases = samples(400);
    let mut totals = [WedgeStats::default(), WedgeStats::default()];
    for _ in 0..cases {
        let case = wedge_case(&mut rng);
        let s = check_wedge_case(&case, &mut rng, 24, true);
        for (t, s) in totals.iter_mut().zip(s) {
            t.affected += s.affected;
            t.missed += s.missed;
            t.undecided += s.undecided;
            t.dropped_planes += s.dropped_planes;
            t.wedges += s.wedges;
        }
    }
    let (mean, worst, used) = wedge_tightness(&mut rng, samples(80), 400);
    if printing() {
        for (name, t) in ["f64", "f32"].iter().zip(&totals) {
            println!(
                "| PenumbraWedge::contains | {name} | {} misses of {} affected receivers ({} undecided); {} planes dropped in {} wedges | wedge_case | {} cases |",
                t.missed, t.affected, t.undecided, t.dropped_planes, t.wedges, cases
            );
        }
        println!(
            "| PenumbraWedge tightness | f64 | in-wedge / affected: mean {mean:.2}, max {worst:.2} | ordinary edges, 400 points in a ball around the edge | {used} cases |"
        );
    }
    assert_eq!(totals[0].missed + totals[1].missed, 0);
    assert!(totals[0].affected > cases);
    assert!(mean >= 1.0);
}

/// `f32` planes against the `f64` planes of the same (f32-representable)
/// input, over edges at least 1% of the radius away from the light and not
/// nearly radial.
#[test]
fn f32_planes_track_f64() {
    let mut rng = Rng::new(0xf32f64);
    let (mut worst, mut n) = (0.0f64, 0usize);
    for _ in 0..samples(2000) {
        let case = wedge_case(&mut rng);
        let (e0, e1, c, r) = (
            case.e0.as_vec3(),
            case.e1.as_vec3(),
            case.light.center.as_vec3(),
            case.light.radius as f32,
        );
        let (e0d, e1d, cd, rd) = (
            DVec3::from(e0),
            DVec3::from(e1),
            DVec3::from(c),
            f64::from(r),
        );
        // Well-conditioned cases only: the segment and its line at least 2 r
        // from the centre, at most 100 r away, the edge at least 0.1 (in
        // sine) off the direction to the light. Nearer, the tangent
        // directions are ill-conditioned (`∝ 1/√(ρ − r)`), and the plane
        // through a radial edge is arbitrary.
        let u = e1d - e0d;
        if u.length_squared() == 0.0 {
            continue;
        }
        let t = ((cd - e0d).dot(u) / u.length_squared()).clamp(0.0, 1.0);
        let dir = u.normalize();
        let line = (e0d - cd) - (e0d - cd).dot(dir) * dir;
        let far = (e0d - cd).length().max((e1d - cd).length());
        let sine = |a: DVec3| dir.cross(a.normalize()).length();
        if !((e0d + t * u - cd).length() >= 2.0 * rd
            && line.length() >= 2.0 * rd
            && far <= 100.0 * rd
            && sine(cd - e0d) >= 0.1
            && sine(cd - e1d) >= 0.1)
        {
            continue;
        }
        let (Ok(a), Ok(b)) = (
            w32::PenumbraWedge::new(e0, e1, c, r),
            w64::PenumbraWedge::new(e0d, e1d, cd, rd),
        ) else {
            continue;
        };
        // Planes are matched by kind; front and back swap when the edge's
        // plane is chosen with the opposite normal (radial edges), so they
        // are matched as a pair. A plane dropped in one precision only is
        // skipped.
        use softshadow::kernel::wedge::WedgePlaneKind::{Back, Front};
        let class = |k| if k == Front || k == Back { Front } else { k };
        for pa in a.planes() {
            let na = DVec3::from(pa.normal).normalize();
            let best = b
                .planes()
                .filter(|pb| class(pb.kind) == class(pa.kind))
                .map(|pb| {
                    let nb = pb.normal.normalize();
                    na.cross(nb).length().atan2(na.dot(nb))
                })
                .fold(f64::INFINITY, f64::min);
            if best.is_finite() {
                worst = worst.max(best / f64::from(f32::EPSILON));
                n += 1;
            }
        }
    }
    if printing() {
        println!("| PenumbraWedge plane normals | f32 vs f64 | {worst:.1} ε_f32 (angle) | wedge_case, well-conditioned (see test) | {n} planes |");
    }
    assert!(worst <= BUDGET_NORMAL_F32, "{worst} ε");
}

// ---------------------------------------------------------------------------
// The penumbra quad (light frame: light at the origin).

fn project(p: DVec3) -> DVec2 {
    DVec2::new(p.x / p.z, p.y / p.z)
}

/// A receiver affected by the edge at depth ≤ z_max, or `None`.
fn quad_receiver(rng: &mut Rng, e0: DVec3, e1: DVec3, r: f64, z_max: f64) -> Option<DVec3> {
    let p = if rng.chance(0.7) {
        constructive_receiver(rng, e0, e1, DVec3::ZERO, r)
    } else {
        // Along the ray through a random image point near the edge's image.
        let w = project(e0 + rng.unit() * (e1 - e0))
            + 0.3
                * rng.log_uniform(-3.0, 0.0)
                * DVec2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        let z = z_max * rng.unit().max(1e-9);
        DVec3::new(w.x * z, w.y * z, z)
    };
    (p.z <= z_max && occlusion(p, e0, e1, DVec3::ZERO, r) == Occlusion::Affected).then_some(p)
}

/// Distance from `w` to the segment `[a, b]`.
fn segment_distance(w: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((w - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * ab - w).length()
}

#[derive(Default)]
struct QuadStats {
    affected: usize,
    missed: usize,
    empty_violations: usize,
    /// max over affected receivers of dist(π(p), projected clipped edge) / R_sism.
    need_over_sism: f64,
    /// the same over the crate's radius.
    need_over_ours: f64,
    /// max of R_ours / R_sism.
    ours_over_sism: f64,
}

fn check_quad(rng: &mut Rng, radius: f64, stats: &mut [QuadStats; 2], receivers: usize) {
    let (e0, e1, z_max) = light_frame_edge(rng, radius);
    let bound64 = w64::penumbra_quad(e0, e1, radius, z_max).unwrap();
    let (e0f, e1f, rf, zf) = (e0.as_vec3(), e1.as_vec3(), radius as f32, z_max as f32);
    let bound32 = w32::penumbra_quad(e0f, e1f, rf, zf).unwrap();
    let (e0p, e1p, rp, zp) = (
        DVec3::from(e0f),
        DVec3::from(e1f),
        f64::from(rf),
        f64::from(zf),
    );
    // f64.
    let z_min = e0.z.min(e1.z);
    for _ in 0..receivers {
        let Some(p) = quad_receiver(rng, e0, e1, radius, z_max) else {
            continue;
        };
        let s = &mut stats[0];
        s.affected += 1;
        match bound64 {
            w64::QuadBound::Quad(q) => {
                let w = project(p);
                let inside = q.contains(w) && w.cmpge(q.min).all() && w.cmple(q.max).all();
                if !inside {
                    s.missed += 1;
                    eprintln!(
                        "f64 quad miss: e0 {e0:?} e1 {e1:?} r {radius} z_max {z_max} p {p:?}"
                    );
                }
                // Clipped edge image, for the radius statistics.
                let (near, far) = if e0.z <= e1.z { (e0, e1) } else { (e1, e0) };
                let far = if far.z > z_max {
                    near + (z_max - near.z) / (far.z - near.z) * (far - near)
                } else {
                    far
                };
                let need = segment_distance(w, project(near), project(far));
                let sism = radius * (1.0 / z_min - 1.0 / z_max);
                s.need_over_sism = s.need_over_sism.max(need / sism);
                s.need_over_ours = s.need_over_ours.max(need / q.radius);
                s.ours_over_sism = s.ours_over_sism.max(q.radius / sism);
            }
            w64::QuadBound::Empty => s.empty_violations += 1,
            w64::QuadBound::Unbounded => {}
        }
    }
    // f32 (inputs rounded, the independent test on the rounded values).
    for _ in 0..receivers {
        let Some(p) = quad_receiver(rng, e0p, e1p, rp, zp) else {
            continue;
        };
        let s = &mut stats[1];
        s.affected += 1;
        match bound32 {
            w32::QuadBound::Quad(q) => {
                let w = project(p);
                // The receiver itself is an f64 point: test the f32 quad's
                // corners exactly in f64.
                let corners = q.corners.map(DVec2::from);
                let inside = (0..4).all(|i| {
                    let (a, b) = (corners[i], corners[(i + 1) % 4]);
                    robust::orient2d(
                        robust::Coord { x: a.x, y: a.y },
                        robust::Coord { x: b.x, y: b.y },
                        robust::Coord { x: w.x, y: w.y },
                    ) >= 0.0
                });
                if !inside {
                    s.missed += 1;
                    eprintln!("f32 quad miss: e0 {e0f:?} e1 {e1f:?} r {rf} z_max {zf} p {p:?}");
                }
            }
            w32::QuadBound::Empty => s.empty_violations += 1,
            w32::QuadBound::Unbounded => {}
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every affected receiver at depth ≤ z_max projects into the quad (its
    /// corners tested with exact orient2d, and its bounding box); an
    /// `Empty` answer has no affected receiver.
    #[test]
    fn quad_never_misses(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let radius = rng.log_uniform(-3.0, 1.0);
        let mut stats = [QuadStats::default(), QuadStats::default()];
        check_quad(&mut rng, radius, &mut stats, 24);
        for s in &stats {
            prop_assert_eq!(s.missed, 0);
            prop_assert_eq!(s.empty_violations, 0);
            prop_assert!(s.need_over_ours <= 1.0);
        }
    }
}

/// Quad area against the sampled true region: image points uniform in the
/// quad's box, each tested at 24 depths up to `z_max`; the true region is
/// under-sampled, so the ratio is an upper estimate.
fn quad_tightness(rng: &mut Rng, cases: usize) -> (f64, usize) {
    let (mut sum, mut used) = (0.0, 0);
    for _ in 0..cases {
        let r = 1.0;
        let z0 = rng.uniform(3.0, 10.0);
        let e0 = DVec3::new(rng.uniform(-0.5, 0.5) * z0, rng.uniform(-0.5, 0.5) * z0, z0);
        let e1 = e0 + z0 * 0.2 * unit_vector(rng);
        if e1.z <= 2.0 * r {
            continue;
        }
        let z_max = e0.z.max(e1.z) * rng.uniform(1.5, 4.0);
        let Ok(w64::QuadBound::Quad(q)) = w64::penumbra_quad(e0, e1, r, z_max) else {
            continue;
        };
        let box_area = (q.max - q.min).x * (q.max - q.min).y;
        let quad_area = 4.0 * q.half_length * q.half_width;
        let mut hits = 0usize;
        let n = 300;
        for _ in 0..n {
            let w = q.min + (q.max - q.min) * DVec2::new(rng.unit(), rng.unit());
            let affected = (1..=24).any(|k| {
                let z = z_max * f64::from(k) / 24.0;
                occlusion(DVec3::new(w.x * z, w.y * z, z), e0, e1, DVec3::ZERO, r)
                    == Occlusion::Affected
            });
            hits += usize::from(affected);
        }
        if hits >= 10 {
            sum += quad_area / (box_area * hits as f64 / n as f64);
            used += 1;
        }
    }
    (sum / used as f64, used)
}

#[test]
fn quad_accuracy_rows() {
    let mut rng = Rng::new(0x9_0ad);
    let cases = samples(400);
    let mut stats = [QuadStats::default(), QuadStats::default()];
    for _ in 0..cases {
        let radius = rng.log_uniform(-3.0, 1.0);
        check_quad(&mut rng, radius, &mut stats, 16);
    }
    // f32 radius against f64 on the same rounded input.
    let mut worst_r = 0.0f64;
    for _ in 0..samples(2000) {
        let radius = rng.log_uniform(-3.0, 1.0) as f32;
        let (e0, e1, z_max) = light_frame_edge(&mut rng, f64::from(radius));
        let (e0, e1, z_max) = (e0.as_vec3(), e1.as_vec3(), z_max as f32);
        if let (Ok(w32::QuadBound::Quad(a)), Ok(w64::QuadBound::Quad(b))) = (
            w32::penumbra_quad(e0, e1, radius, z_max),
            w64::penumbra_quad(
                DVec3::from(e0),
                DVec3::from(e1),
                f64::from(radius),
                f64::from(z_max),
            ),
        ) {
            worst_r =
                worst_r.max((f64::from(a.radius) / b.radius - 1.0).abs() / f64::from(f32::EPSILON));
        }
    }
    let (area_ratio, used) = quad_tightness(&mut rng, samples(30));
    if printing() {
        for (name, s) in ["f64", "f32"].iter().zip(&stats) {
            println!(
                "| penumbra_quad | {name} | {} misses of {} affected receivers | light_frame_edge | {cases} cases |",
                s.missed, s.affected
            );
        }
        let s = &stats[0];
        println!(
            "| penumbra_quad radius | f64 | needed/R_ours max {:.3}; needed/R_SISM max {:.3}; R_ours/R_SISM max {:.3} | light_frame_edge | {} receivers |",
            s.need_over_ours, s.need_over_sism, s.ours_over_sism, s.affected
        );
        println!("| penumbra_quad radius | f32 vs f64 | {worst_r:.1} ε_f32 relative | light_frame_edge | {} |", samples(2000));
        println!("| penumbra_quad tightness | f64 | quad area / sampled true region: mean {area_ratio:.2} | edges 3–10 r deep | {used} cases |");
    }
    for s in &stats {
        assert_eq!(s.missed + s.empty_violations, 0);
    }
    assert!(stats[0].need_over_ours <= 1.0);
    assert!(worst_r <= BUDGET_QUAD_RADIUS_F32, "{worst_r}");
    assert!(area_ratio >= 1.0);
}
