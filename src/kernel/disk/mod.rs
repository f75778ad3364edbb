//! Disk occlusion: how much of a disk a polygon covers.
//!
//! The [receiver view](crate::definitions#receiver-view) of an area light turns visibility into a
//! planar question: the light is a disk of radius `R` centred at the origin,
//! the occluders are polygons, and `V = 1 − area(∪ polygons ∩ disk) / πR²`.
//! This module answers it exactly, edge by edge:
//!
//! - [`f64::segment_disk_area`]: the signed area of the triangle `(0, a, b)`
//!   intersected with the disk. By Green's theorem the sum over the oriented
//!   boundary of any polygon is `area(polygon ∩ disk)`, whatever the polygon's
//!   shape: corners inside the disk and several edges crossing it need no
//!   special case.
//! - [`f64::polygon_disk_area`]: that sum, compensated.
//! - [`f64::circle_segment_occlusion`]: Johnson et al.'s eq. 3 (SISM), the
//!   signed normalised area of the circular segment cut by one clipped edge.
//! - [`f64::segment_disk_areas`], [`f64::circle_segment_occlusions`]: the
//!   two of many edges at once, bit for bit, several edges per
//!   instruction.
//!
//! All exist in `f32` and `f64` ([`mod@f32`], [`mod@f64`]) from one body.
//!
//! ## Numerics
//!
//! - Angles come from `atan2(cross, dot)`, never from `acos` of a computed
//!   cosine. The cross product of the input points, which decides the
//!   distance of an edge from the centre, is formed from exact products
//!   (error-free transformations), so it keeps about one ulp of relative
//!   accuracy under cancellation and is exactly antisymmetric.
//! - An edge is measured in its own frame (distance `g` of its line from the
//!   centre, positions `t` along it) from quantities computed directly from
//!   the inputs: `g = (a × b) / |b − a|` — no foot-of-perpendicular point
//!   that loses digits when the edge is a million times longer than `R`.
//! - The chord half-length is `√((R − |g|)(R + |g|))`: no cancellation as
//!   the line becomes tangent.
//! - `θ − sin θ` for thin circular segments comes from its Taylor series,
//!   not from the subtraction.
//! - Inputs whose magnitudes leave a safe range are rescaled by an exact
//!   power of two, so products neither overflow nor underflow and the
//!   relative accuracy holds over the whole floating-point range.
//!
//! Measured accuracy: `docs/accuracy/kernels.md` (regenerate with the command
//! given there).

mod area;
mod edge;
mod occlusion;

use crate::kernel::float::both_precisions;

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use super::{area, occlusion};
        use glam::$V2;

        /// Signed area of the triangle `(0, a, b)` intersected with the disk
        /// of radius `r` centred at the origin.
        ///
        /// Positive when `0, a, b` turn counter-clockwise (the origin lies to
        /// the left of `a → b`), negative when clockwise, zero when they are
        /// collinear. Summed over the oriented boundary of a polygon it gives
        /// the polygon's signed area inside the disk (Green's theorem): see
        /// [`polygon_disk_area`].
        ///
        /// **Domain**: all finite `a`, `b` and `r ≥ 0`. The result depends
        /// only on the shape, and inputs are rescaled by an exact power of two
        /// when needed, so the accuracy below holds at any magnitude provided
        /// `r ≥ 10⁻¹⁰⁰ · max|coordinate|` (`f64`; `10⁻¹²` for `f32`). Beyond
        /// that ratio the sector angles' intermediate products underflow and
        /// the area, of order `r²`, is lost (measured: 456 ε r² at a ratio of
        /// `10⁻¹⁰⁴`, the sectors dropped entirely below `10⁻¹⁰⁸`). Where the
        /// area itself is subnormal (`r ≲ 10⁻¹⁵⁴`, `f32`: `10⁻¹⁹`) its error
        /// is that of the subnormal spacing, not a multiple of `ε r²`.
        ///
        /// **Edge of the domain**: `r = 0`, a zero-length edge, or `0, a, b`
        /// collinear give `0`. Endpoints on the circle, the line tangent to
        /// the circle, and edges far longer than `r` need no special case.
        /// Non-finite input (NaN or ±∞ anywhere) or a negative `r` gives `0`.
        /// The result overflows to ±∞ only if the true area does.
        ///
        /// Reversing the edge negates the result exactly (bit for bit).
        ///
        /// **Accuracy**: absolute error at most `3 ε r²` (the tested
        /// budget; measured maximum against a 256-bit evaluation of a
        /// different formulation over 1.5·10⁵ stiff edges: `1.96 ε r²` in
        /// `f64`, `1.70 ε r²` in `f32`; `docs/accuracy/kernels.md`).
        ///
        /// **Source**: the standard decomposition into a triangle inside the
        /// disk and circular sectors outside it, in the edge's own frame.
        #[must_use]
        pub fn segment_disk_area(r: $T, a: $V2, b: $V2) -> $T {
            area::segment_disk_area(r, a, b)
        }

        /// [`segment_disk_area`] of many edges: `out` is replaced by one area
        /// per edge, `out[i]` equal to `segment_disk_area(r, edges[i].0,
        /// edges[i].1)` bit for bit (same domain, same accuracy, same
        /// special values).
        ///
        /// Faster per edge than a loop over [`segment_disk_area`]: the edges
        /// are evaluated without branches, several at once — auto-vectorised
        /// for the build's target, and with the `simd` feature on x86-64 in
        /// AVX2 registers with hardware FMA where the processor has them
        /// (detected at run time). Edges the branch-free form does not cover
        /// (non-finite or very large coordinates, `r` outside the kernel's
        /// safe range, an angle with both parts zero) are evaluated by
        /// [`segment_disk_area`] itself. `benches/README.md` gives the
        /// measured cost.
        pub fn segment_disk_areas(r: $T, edges: &[($V2, $V2)], out: &mut Vec<$T>) {
            area::segment_disk_areas(r, edges, out)
        }

        /// Signed area of the polygon `vertices` intersected with the disk of
        /// radius `r` centred at the origin: the sum of
        /// [`segment_disk_area`] over its edges, the closing edge included,
        /// accumulated with Neumaier's compensated summation.
        ///
        /// Positive for a counter-clockwise polygon, negative for a clockwise
        /// one. For a self-intersecting polygon it is the winding-number
        /// weighted area inside the disk (the general form of Green's
        /// theorem).
        ///
        /// When no edge comes within `r` of the centre the answer is exact:
        /// `0` for a polygon that misses the disk, `±πr²` (times the winding
        /// number) for one that contains it, decided with the exact
        /// [`orient2d`](crate::kernel::predicate::orient2d). Fully lit and
        /// fully covered lights therefore read exactly 1 and 0.
        ///
        /// **Edge of the domain**: fewer than three vertices give `0`;
        /// non-finite vertices contribute `0` for their two edges, as in
        /// [`segment_disk_area`]. A radius so large that `πr²` overflows gives
        /// ±∞ or a finite value, never NaN.
        ///
        /// **Accuracy**: each edge as [`segment_disk_area`]; the compensated
        /// sum adds no error growing with the number of edges. Tested budget
        /// `5 ε r²` (measured maximum over 2·10⁴ stiff polygons of 3–12
        /// vertices, long grazing edges included: `4.29 ε r²` in `f64`,
        /// `3.53 ε r²` in `f32`).
        #[must_use]
        pub fn polygon_disk_area(r: $T, vertices: &[$V2]) -> $T {
            area::polygon_disk_area(r, vertices)
        }

        /// Johnson et al.'s signed circle-segment occlusion (SISM, I3D 2009,
        /// eq. 3), for the unit disk: the normalised area of the circular
        /// segment cut by one silhouette edge, with the edge clipped to the
        /// disk.
        ///
        /// The edge lies on the line at distance `|d|` from the disk centre;
        /// its clipped endpoints are at positions `−w0` and `+w1` along the
        /// line, measured from the foot of the perpendicular (so `w0 + w1` is
        /// the clipped length and the paper's
        /// `θ = acos((d² − w0 w1)/√((d² + w0²)(d² + w1²)))` is the angle the
        /// clipped edge subtends at the centre). The result is
        ///
        /// `± (θ − |d|(w0 + w1)) / 2π`,
        ///
        /// positive when `d` is positive (the centre, i.e. the receiver, lies
        /// outside the edge: the occluder covers the minor segment),
        /// negative when `d` is negative (the receiver is inside the edge and
        /// counted by the umbra pass, so the minor segment is visible light
        /// to subtract). The sign is read from `d`'s sign bit, so `−0.0`
        /// selects the inside: at `|d| = 0` the value jumps by one half, as
        /// the umbra count jumps by one.
        ///
        /// **Domain**: any finite `d`, `w0`, `w1`. Endpoints beyond the circle
        /// are clipped to it (`|w| ≤ √(1 − d²)`), as the paper assumes they
        /// are; `|d| ≥ 1` gives `0`. A reversed edge (`w0 + w1 < 0`) gives the
        /// negated value, so the kernel is additive when an edge is split
        /// anywhere. `d = 0` is the limit `d → 0⁺`: an endpoint at the centre
        /// subtends a right angle on its side. Non-finite input gives `0`.
        ///
        /// **Accuracy**: `θ` from `atan2(|d|(w0 + w1), d² − w0 w1)`, never
        /// `acos`; for thin segments `θ − sin θ` comes from its series and
        /// the remainder `(1 − ρ) sin θ`, `ρ = |p0||p1|`, is computed without
        /// cancellation, so slivers keep their relative accuracy. Measured
        /// against a 256-bit evaluation of the endpoint-angle form: absolute
        /// error ≤ `0.56 ε` over 1.5·10⁵ stiff edges (budget `1 ε`); relative
        /// error of thin full-chord segments down to `h = 1 − 10⁻¹⁵`
        /// ≤ `8 ε` (budget `9 ε`), both precisions.
        #[must_use]
        pub fn circle_segment_occlusion(d: $T, w0: $T, w1: $T) -> $T {
            occlusion::circle_segment_occlusion(d, w0, w1)
        }

        /// [`circle_segment_occlusion`] of many edges: `out` is replaced by
        /// one value per edge, `out[i]` equal to
        /// `circle_segment_occlusion(d, w0, w1)` of `edges[i] = (d, w0, w1)`
        /// bit for bit (same domain, accuracy and special values).
        ///
        /// Faster per edge than a loop over [`circle_segment_occlusion`]:
        /// the edges are evaluated without branches, several at once, as in
        /// [`segment_disk_areas`] (AVX2 where the processor has it, with the
        /// `simd` feature). Edges the branch-free form does not cover
        /// (non-finite input, `|d|` at least 1 or nonzero below the
        /// kernel's safe range, an edge of zero length after clipping) are
        /// evaluated by [`circle_segment_occlusion`] itself.
        /// `benches/README.md` gives the measured cost.
        pub fn circle_segment_occlusions(edges: &[($T, $T, $T)], out: &mut Vec<$T>) {
            occlusion::circle_segment_occlusions(edges, out)
        }
    };
}

both_precisions!(precision);
