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

macro_rules! disk_kernels {
    ($T:ident, $V2:ident, $SAFE_LO:expr, $SAFE_HI:expr) => {
        use glam::$V2;

        const PI: $T = core::$T::consts::PI;

        /// With the radius at least `SAFE_LO` and every magnitude at most
        /// `SAFE_HI`, every intermediate product (up to the fourth power of a
        /// coordinate, and `(|p| r)²` with a cancellation margin) stays in the
        /// normal range.
        const SAFE_LO: $T = $SAFE_LO;
        const SAFE_HI: $T = $SAFE_HI;

        use crate::kernel::angle::$T::{self as angle, atan2};
        use crate::kernel::eft::$T::{two_prod, two_prod_fma};
        use crate::kernel::lanes::{self, Lanes, Real};

        /// Edges evaluated side by side by [`segment_disk_areas`]: four, one
        /// AVX2 register of `f64` (of `f32`, half of one: eight `f32` lanes
        /// measured twice as slow, the compiler's eight-wide code spilling
        /// and converting masks).
        const LANES: usize = 4;

        /// The 2D cross product `p × q`, accurate to about one ulp even
        /// under cancellation (both products exactly, then their
        /// difference), and exactly antisymmetric: `cross(q, p)` is
        /// `−cross(p, q)` bit for bit.
        #[inline(always)]
        fn cross(p: $V2, q: $V2) -> $T {
            cross_by::<$T, false>(p.x, p.y, q.x, q.y)
        }

        /// [`cross`] of `(px, py)` and `(qx, qy)`, on one value or on lanes,
        /// its exact products by a fused multiply-add when `FMA` (for code
        /// compiled where a hardware FMA is enabled): the same bits.
        #[inline(always)]
        fn cross_by<R: Real<Scalar = $T>, const FMA: bool>(px: R, py: R, qx: R, qy: R) -> R {
            let prod = if FMA { two_prod_fma } else { two_prod };
            let (s, se) = prod(px, qy);
            let (t, te) = prod(py, qx);
            (s - t) + (se - te)
        }

        /// The dot product `p · q`, plainly rounded: its absolute error
        /// `ε |p| |q|` costs the angles and positions it feeds no more than
        /// their own rounding.
        #[inline(always)]
        fn dot(p: $V2, q: $V2) -> $T {
            dot_of(p.x, p.y, q.x, q.y)
        }

        /// [`dot`] of `(px, py)` and `(qx, qy)`, on one value or on lanes.
        #[inline(always)]
        fn dot_of<R: Real>(px: R, py: R, qx: R, qy: R) -> R {
            px * qx + py * qy
        }

        /// `2^e` for `|e|` below the exponent range, exactly.
        #[inline]
        fn pow2(e: i32) -> $T {
            (2.0 as $T).powi(e)
        }

        /// The exponent `e` for which `x · 2^-e` lies near 1, clamped so that
        /// `2^-e` is finite.
        #[inline]
        fn rescale_exponent(x: $T) -> i32 {
            let limit = <$T>::MAX_EXP - 2;
            (x.log2().floor() as i32).clamp(-limit, limit)
        }

        /// `1 / (n (n + 1))` for `n = 4, 6, …, 18`: the ratios of successive
        /// terms of the sine series, `θ^(n+1)/(n+1)! = θ^(n−1)/(n−1)! ·
        /// θ²/(n (n + 1))`.
        const SINE_RATIOS: [$T; 8] = {
            let mut c = [0.0; 8];
            let mut j = 0;
            while j < 8 {
                let n = (2 * j + 4) as $T;
                c[j] = 1.0 / (n * (n + 1.0));
                j += 1;
            }
            c
        };

        /// `θ − sin θ` for `0 ≤ θ < 1`, with full relative accuracy, from the
        /// Taylor series `θ³/3! − θ⁵/5! + …` in nested form,
        /// `θ³/6 · (1 − θ²/(4·5) (1 − θ²/(6·7) (1 − …)))`, up to `θ¹⁹/19!`;
        /// the first omitted term, `θ²¹/21!`, is below 2⁻⁶⁵ of the sum on
        /// that interval. (No libm `sin`: the result is the same on every
        /// platform.)
        #[inline(always)]
        fn theta_minus_sin<R: Real<Scalar = $T>>(theta: R) -> R {
            let x2 = theta * theta;
            let mut s = R::splat(1.0);
            for &c in SINE_RATIOS.iter().rev() {
                s = R::splat(1.0) - x2 * R::splat(c) * s;
            }
            theta * x2 / R::splat(6.0) * s
        }

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
            if !(r > 0.0 && r.is_finite() && a.is_finite() && b.is_finite()) {
                return 0.0;
            }
            let m = a.abs().max_element().max(b.abs().max_element()).max(r);
            if m <= SAFE_HI && r >= SAFE_LO {
                return area_in_range(r, a, b);
            }
            // Rescale by an exact power of two; the area scales by its square.
            let e = rescale_exponent(m);
            let s = pow2(-e);
            let back = pow2(e);
            area_in_range(r * s, a * s, b * s) * back * back
        }

        /// [`segment_disk_area`] for finite input of moderate magnitude.
        ///
        /// Every step is exactly antisymmetric in `a ↔ b` (negations,
        /// commuted sums and products, an odd `atan2`), which is what makes
        /// reversing the edge negate the result bit for bit.
        #[inline(always)]
        fn area_in_range(r: $T, a: $V2, b: $V2) -> $T {
            let ab_cross = cross(a, b);
            if ab_cross == 0.0 {
                // Collinear with the centre, or a zero-length edge.
                return 0.0;
            }
            let r2 = r * r;
            if dot(a, a) <= r2 && dot(b, b) <= r2 {
                // Both endpoints inside: the whole triangle.
                return 0.5 * ab_cross;
            }
            let (g, ta, tb) = edge_frame(a.x, a.y, b.x, b.y, ab_cross);
            let abs_g = g.abs();
            if abs_g >= r {
                // The whole edge lies outside: one circular sector.
                return 0.5 * r2 * atan2(ab_cross, dot(a, b));
            }
            let w = half_chord(r, abs_g);
            if tb <= -w || ta >= w {
                return 0.5 * r2 * atan2(ab_cross, dot(a, b));
            }
            let (triangle, outside, im, re) = crossing_pieces(g, w, ta, tb);
            if !outside {
                return triangle;
            }
            triangle + 0.5 * r2 * atan2(im, re)
        }

        /// The edge `a → b` in its own frame, from `a × b`: the distance `g`
        /// of its line from the centre, signed by the orientation, and the
        /// positions `ta < tb` of its ends along its direction, measured from
        /// the foot of the perpendicular from the centre.
        #[inline(always)]
        fn edge_frame<R: Real<Scalar = $T>>(ax: R, ay: R, bx: R, by: R, ab_cross: R) -> (R, R, R) {
            let (dx, dy) = (bx - ax, by - ay);
            let inv_len = R::splat(1.0) / dot_of(dx, dy, dx, dy).sqrt();
            (
                ab_cross * inv_len,
                dot_of(ax, ay, dx, dy) * inv_len,
                dot_of(bx, by, dx, dy) * inv_len,
            )
        }

        /// Half the chord the line at distance `|g| < r` cuts from the
        /// circle, `√((r − |g|)(r + |g|))`: no cancellation as the line
        /// becomes tangent. The disk spans `[−w, w]` in the edge's frame.
        #[inline(always)]
        fn half_chord<R: Real>(r: R, abs_g: R) -> R {
            ((r - abs_g) * (r + abs_g)).sqrt()
        }

        /// The pieces of an edge that crosses the circle, in its frame
        /// (distance `g`, the disk spanning `[−w, w]`, endpoints at `ta <
        /// tb`, overlapping it): the triangle inside the disk, whether a piece
        /// lies outside, and the complex number `re + i im` whose argument is
        /// the outside pieces' angle.
        #[inline(always)]
        fn crossing_pieces<R: Real<Scalar = $T>>(g: R, w: R, ta: R, tb: R) -> (R, R::Mask, R, R) {
            let k = |x: $T| R::splat(x);
            // The piece inside the disk is a triangle of height g.
            let triangle = k(0.5) * g * (tb.min(w) - ta.max(-w));
            // The pieces outside are sectors. The angle between the points at
            // t1 < t2 is arg(t1 t2 + g² + i g (t2 − t1)); when both pieces
            // exist their angles are summed as one complex product (the sum
            // stays below π, as the triangle's angle at the origin does).
            let g2 = g * g;
            let before = ta.lt(-w);
            let after = tb.gt(w);
            let re1 = R::select(before, -w * ta + g2, k(1.0));
            let im1 = R::select(before, g * (-w - ta), k(0.0));
            let re2 = R::select(after, w * tb + g2, k(1.0));
            let im2 = R::select(after, g * (tb - w), k(0.0));
            let re = re1 * re2 - im1 * im2;
            let im = re1 * im2 + im1 * re2;
            (triangle, before | after, im, re)
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
            if (SAFE_LO..=SAFE_HI).contains(&r) {
                batch(
                    edges,
                    out,
                    #[inline(always)]
                    |fma, edges, out| {
                        if fma {
                            areas_branch_free::<true>(r, edges, out)
                        } else {
                            areas_branch_free::<false>(r, edges, out)
                        }
                    },
                    |(a, b)| segment_disk_area(r, a, b),
                );
            } else {
                out.clear();
                out.extend(edges.iter().map(|&(a, b)| segment_disk_area(r, a, b)));
            }
        }

        /// `out` replaced by one value per input: `branch_free(fma, inputs,
        /// out)` (compiled for AVX2 and FMA where the processor has them,
        /// `fma` saying whether it is; the answer whether it left any entry
        /// `NaN`), then `one` for each entry so left — which the one-input
        /// kernels never return.
        #[inline(always)]
        fn batch<E: Copy>(
            inputs: &[E],
            out: &mut Vec<$T>,
            branch_free: impl FnOnce(bool, &[E], &mut [$T]) -> bool,
            one: impl Fn(E) -> $T,
        ) {
            // Every entry is overwritten: only new ones are zeroed first.
            out.truncate(inputs.len());
            out.resize(inputs.len(), 0.0);
            let marked = lanes::vectorized(
                #[inline(always)]
                |fma| branch_free(fma, inputs, out),
            );
            if marked {
                for (o, &e) in out.iter_mut().zip(inputs) {
                    if o.is_nan() {
                        *o = one(e);
                    }
                }
            }
        }

        /// Edges per block of [`areas_branch_free`]: its scratch array stays
        /// on the stack and in the first-level cache.
        const BLOCK: usize = 16 * LANES;

        /// The edges in blocks of up to [`BLOCK`], each in two passes over
        /// [`LANES`] edges at a time (the last group padded with zero-length
        /// edges): [`frame_of_lanes`], then the angle and the answer
        /// ([`finish_lanes`]). Two short loops rather than one long one: the
        /// processor overlaps several groups' latency chains (square roots,
        /// divisions) only when a group's instructions are few. `out` is as
        /// long as `edges`; the answer is whether any entry was left `NaN`
        /// for the scalar path. (Functions, not closures: a closure would be
        /// compiled apart, without the caller's target features.)
        #[inline(always)]
        fn areas_branch_free<const FMA: bool>(r: $T, edges: &[($V2, $V2)], out: &mut [$T]) -> bool {
            type L = Lanes<$T, LANES>;
            #[inline(always)]
            fn frame<const FMA: bool>(r: L, r2: L, e: &[($V2, $V2); LANES]) -> Frame<L> {
                let coord =
                    |pick: fn(&($V2, $V2)) -> $T| Lanes(core::array::from_fn(|i| pick(&e[i])));
                frame_of_lanes::<L, FMA>(
                    r,
                    r2,
                    coord(|e| e.0.x),
                    coord(|e| e.0.y),
                    coord(|e| e.1.x),
                    coord(|e| e.1.y),
                )
            }
            let (r, r2) = (L::splat(r), L::splat(r * r));
            let mut frames = [Frame::<L>::default(); BLOCK / LANES];
            // Lanes marked NaN for the scalar path (a padding lane never is).
            let mut marked = <L as Real>::Mask::default();
            for (o, e) in out.chunks_mut(BLOCK).zip(edges.chunks(BLOCK)) {
                let groups = e.chunks_exact(LANES);
                let rest = groups.remainder();
                let mut n = 0;
                for (f, g) in frames.iter_mut().zip(groups) {
                    if let Ok(g) = <&[($V2, $V2); LANES]>::try_from(g) {
                        *f = frame::<FMA>(r, r2, g);
                        n += 1;
                    }
                }
                if !rest.is_empty() {
                    let mut padded = [($V2::ZERO, $V2::ZERO); LANES];
                    padded[..rest.len()].copy_from_slice(rest);
                    if let Some(f) = frames.get_mut(n) {
                        *f = frame::<FMA>(r, r2, &padded);
                    }
                }
                let mut outs = o.chunks_exact_mut(LANES);
                for (f, o) in frames.iter().zip(&mut outs) {
                    let areas = finish_lanes(r2, f);
                    marked = marked | !areas.eq(areas);
                    o.copy_from_slice(&areas.0);
                }
                let o = outs.into_remainder();
                if let Some(f) = frames.get(n).filter(|_| !o.is_empty()) {
                    let areas = finish_lanes(r2, f);
                    marked = marked | !areas.eq(areas);
                    o.copy_from_slice(&areas.0[..o.len()]);
                }
            }
            L::any(marked)
        }

        /// What [`frame_of_lanes`] leaves for [`finish_lanes`]: the answer
        /// without its angle (`pre`), the angle's `atan2(y, x)` arguments,
        /// and whether the answer is the sector alone or `pre` plus it.
        #[derive(Clone, Copy, Default)]
        struct Frame<R: Real> {
            pre: R,
            y: R,
            x: R,
            sector: R::Mask,
            plus_sector: R::Mask,
        }

        /// [`area_in_range`] of edges side by side, as straight-line code
        /// (every path computed, the answer selected), up to the angle.
        /// `pre` is `NaN` for an edge that needs the scalar path. `r` lies in
        /// the safe range.
        #[inline(always)]
        fn frame_of_lanes<R: Real<Scalar = $T>, const FMA: bool>(
            r: R,
            r2: R,
            ax: R,
            ay: R,
            bx: R,
            by: R,
        ) -> Frame<R> {
            let k = |x: $T| R::splat(x);
            let (aa, bb) = (dot_of(ax, ay, ax, ay), dot_of(bx, by, bx, by));
            // Within the safe range (every coordinate at most SAFE_HI, none
            // NaN) when |a|, |b| ≤ SAFE_HI: stricter than the scalar test, so
            // a few edges near its limit take the scalar path needlessly,
            // never the other way round.
            let hi2 = k(SAFE_HI * SAFE_HI);
            let in_range = aa.le(hi2) & bb.le(hi2);
            let ab_cross = cross_by::<R, FMA>(ax, ay, bx, by);
            let zero = ab_cross.eq(k(0.0));
            let inside = aa.le(r2) & bb.le(r2);
            let (g, ta, tb) = edge_frame(ax, ay, bx, by, ab_cross);
            let abs_g = g.abs();
            let w = half_chord(r, abs_g);
            let sector = abs_g.ge(r) | tb.le(-w) | ta.ge(w);
            let (triangle, outside, im, re) = crossing_pieces(g, w, ta, tb);
            let pre = R::select(inside, k(0.5) * ab_cross, triangle);
            let pre = R::select(in_range, pre, k(<$T>::NAN));
            let angle = !zero & in_range & !inside;
            Frame {
                pre: R::select(zero, k(0.0), pre),
                y: R::select(sector, ab_cross, im),
                x: R::select(sector, dot_of(ax, ay, bx, by), re),
                sector: angle & sector,
                plus_sector: angle & !sector & outside,
            }
        }

        /// The answer of a [`Frame`]: `pre`, the sector, or their sum;
        /// `NaN` where the angle has no regular value (both parts zero).
        #[inline(always)]
        fn finish_lanes<R: Real<Scalar = $T>>(r2: R, f: &Frame<R>) -> R {
            let (num, den, swap, regular) = angle::reduce(f.y, f.x);
            let angle_term = R::splat(0.5) * r2 * angle::core(num, den, swap, f.x, f.y);
            let value = R::select(
                f.sector,
                angle_term,
                R::select(f.plus_sector, f.pre + angle_term, f.pre),
            );
            R::select(
                (f.sector | f.plus_sector) & !regular,
                R::splat(<$T>::NAN),
                value,
            )
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
            if vertices.len() < 3 || !(r > 0.0 && r.is_finite()) {
                return 0.0;
            }
            // Rescale by an exact power of two when the disk or the polygon
            // leaves the safe range: no product in the edge tests overflows,
            // no edge's area overflows, and the sum never meets ∞ − ∞.
            let m = vertices
                .iter()
                .filter(|v| v.is_finite())
                .fold(r, |m, v| m.max(v.abs().max_element()));
            let (s, back) = if m <= SAFE_HI && r >= SAFE_LO {
                (1.0, 1.0)
            } else {
                let e = rescale_exponent(m);
                (pow2(-e), pow2(e))
            };
            let rs = r * s;
            let r2 = rs * rs;
            // The exact answer when no edge comes within r of the centre (a
            // closed polygon: every vertex finite).
            if vertices.iter().all(|v| v.is_finite()) {
                let mut touches = false;
                let mut winding: i64 = 0;
                let mut prev = vertices[vertices.len() - 1] * s;
                for &v in vertices {
                    let v = v * s;
                    touches = touches || edge_meets_disk(prev, v, r2);
                    winding += crossing(prev, v);
                    prev = v;
                }
                if !touches {
                    return winding as $T * PI * r2 * back * back;
                }
            }
            let mut sum: $T = 0.0;
            let mut comp: $T = 0.0;
            let mut prev = vertices[vertices.len() - 1] * s;
            for &v in vertices {
                let v = v * s;
                let x = segment_disk_area(rs, prev, v);
                let t = sum + x;
                comp += if sum.abs() >= x.abs() {
                    (sum - t) + x
                } else {
                    (x - t) + sum
                };
                sum = t;
                prev = v;
            }
            (sum + comp) * back * back
        }

        /// Whether the segment `a b` comes within `√r2` of the centre. The
        /// distance of the line is `|a × b| / |b − a|` from the accurate
        /// cross product (a foot point `a + t (b − a)` would be off by
        /// `ε |b − a|`, far more than `r` for long edges); the decision can
        /// err only within a few ulps of tangency, where the overlap it
        /// would miss is far below the kernel's error.
        #[inline]
        fn edge_meets_disk(a: $V2, b: $V2, r2: $T) -> bool {
            if dot(a, a) < r2 || dot(b, b) < r2 {
                return true;
            }
            let d = b - a;
            // The foot of the perpendicular lies inside the segment.
            let interior = dot(a, d) < 0.0 && dot(b, d) > 0.0;
            let c = cross(a, b);
            interior && c * c < r2 * dot(d, d)
        }

        /// This edge's contribution to the winding number of the origin
        /// (`+1` upward crossing with the origin on the left, `−1` downward
        /// with it on the right, the half-open rule on `y`), decided exactly.
        #[inline]
        fn crossing(a: $V2, b: $V2) -> i64 {
            use crate::kernel::predicate::{orient2d, Sign};
            // Promotion to f64 is exact for both precisions.
            let wide = |p: $V2| glam::DVec2::new(p.x as f64, p.y as f64);
            let side = || orient2d(wide(a), wide(b), glam::DVec2::ZERO);
            if a.y <= 0.0 {
                if b.y > 0.0 && side() == Sign::Positive {
                    return 1;
                }
            } else if b.y <= 0.0 && side() == Sign::Negative {
                return -1;
            }
            0
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
            if !(d.is_finite() && w0.is_finite() && w1.is_finite()) {
                return 0.0;
            }
            let sign: $T = if d.is_sign_negative() { -1.0 } else { 1.0 };
            let d = d.abs();
            if d >= 1.0 {
                return 0.0;
            }
            // Clip to the chord: the endpoints' positions are −w0 and +w1.
            let s = ((1.0 - d) * (1.0 + d)).sqrt();
            let w0 = w0.clamp(-s, s);
            let w1 = w1.clamp(-s, s);
            let length = w0 + w1;
            if length == 0.0 {
                return 0.0;
            }
            if d == 0.0 {
                // The limit d → 0⁺: each endpoint's angle from the
                // perpendicular is ±π/2 (0 at the centre itself).
                let half_turns = |w: $T| {
                    if w == 0.0 {
                        0.0
                    } else {
                        0.5 * w.signum()
                    }
                };
                return sign * (half_turns(w0) + half_turns(w1)) * 0.5;
            }
            // The complex product (d + i·w1)(d + i·w0) has argument θ. θ is
            // scale-invariant: tiny inputs are scaled up (exactly) first, so
            // that its parts do not underflow.
            let c = d * length;
            let big = d.max(w0.abs()).max(w1.abs());
            let k = if big < SAFE_LO {
                pow2(-rescale_exponent(big))
            } else {
                1.0
            };
            let (dk, w0k, w1k) = (d * k, w0 * k, w1 * k);
            let theta = if dk >= SAFE_LO {
                atan2(dk * (w0k + w1k), dk * dk - w0k * w1k)
            } else {
                // d far below the endpoints' distances: the products would
                // underflow, so add the endpoints' angles instead.
                atan2(w1k, dk) + atan2(w0k, dk)
            };
            let abs_theta = theta.abs();
            // θ − ρ sin θ with c = ρ sin θ: split as (θ − sin θ) + (1 − ρ) sin θ
            // when θ is small and both terms are small; directly otherwise.
            let value = if abs_theta < 1.0 {
                let (rho, one_minus_rho2) = rho_of(d, w0, w1, s);
                // c = ρ sin θ; ρ underflows only for endpoints at the centre.
                let sin_theta = if rho > 0.0 {
                    c.abs() / rho
                } else {
                    abs_theta.sin()
                };
                thin_value(theta, sin_theta, rho, one_minus_rho2)
            } else {
                theta - c
            };
            sign * value / (2.0 * PI)
        }

        /// `ρ = |p0||p1|` for the clipped endpoints `p0 = (d, −w0)`, `p1 =
        /// (d, w1)`, and `1 − ρ²` without cancellation near the circle (`s`
        /// the half chord).
        #[inline(always)]
        fn rho_of<R: Real<Scalar = $T>>(d: R, w0: R, w1: R, s: R) -> (R, R) {
            let r0 = d * d + w0 * w0;
            let r1 = d * d + w1 * w1;
            // 1 − ρ² = a0 + a1 − a0 a1, with a = 1 − |p|² = s² − w²
            // = (s − w)(s + w): no cancellation near the circle.
            let a0 = (s - w0.abs()) * (s + w0.abs());
            let a1 = (s - w1.abs()) * (s + w1.abs());
            let one_minus_rho2 = (a0 + a1 - a0 * a1).max(R::splat(0.0));
            ((r0 * r1).sqrt(), one_minus_rho2)
        }

        /// `θ − ρ sin θ` for `|θ| < 1`, as `(θ − sin θ) + (1 − ρ) sin θ`.
        #[inline(always)]
        fn thin_value<R: Real<Scalar = $T>>(
            theta: R,
            sin_theta: R,
            rho: R,
            one_minus_rho2: R,
        ) -> R {
            let rest = one_minus_rho2 / (R::splat(1.0) + rho) * sin_theta;
            (theta_minus_sin(theta.abs()) + rest).copysign(theta)
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
            batch(
                edges,
                out,
                #[inline(always)]
                |_, edges, out| occlusions_branch_free(edges, out),
                |(d, w0, w1)| circle_segment_occlusion(d, w0, w1),
            );
        }

        /// [`circle_segment_occlusions`]' loop, [`LANES`] edges at a time
        /// (the last group padded with a regular edge); `out` as long as
        /// `edges`; the answer is whether any entry was left `NaN` for the
        /// scalar path.
        #[inline(always)]
        fn occlusions_branch_free(edges: &[($T, $T, $T)], out: &mut [$T]) -> bool {
            type L = Lanes<$T, LANES>;
            #[inline(always)]
            fn group(e: &[($T, $T, $T)]) -> L {
                let lane = |pick: fn(&($T, $T, $T)) -> $T| {
                    Lanes(core::array::from_fn(|i| e.get(i).map_or(0.5, pick)))
                };
                occlusion_lanes::<L>(lane(|e| e.0), lane(|e| e.1), lane(|e| e.2))
            }
            let mut marked = <L as Real>::Mask::default();
            for (o, e) in out.chunks_mut(LANES).zip(edges.chunks(LANES)) {
                let values = group(e);
                marked = marked | !values.eq(values);
                o.copy_from_slice(&values.0[..o.len()]);
            }
            L::any(marked)
        }

        /// [`circle_segment_occlusion`] side by side, as straight-line code;
        /// `NaN` for an edge the scalar path must take (see
        /// [`circle_segment_occlusions`]).
        #[inline(always)]
        fn occlusion_lanes<R: Real<Scalar = $T>>(d: R, w0: R, w1: R) -> R {
            let k = |x: $T| R::splat(x);
            // Finite: `x − x` is 0 exactly then.
            let finite = (d - d).eq(k(0.0)) & (w0 - w0).eq(k(0.0)) & (w1 - w1).eq(k(0.0));
            let sign = R::select(d.is_sign_negative(), k(-1.0), k(1.0));
            let d = d.abs();
            let s = ((k(1.0) - d) * (k(1.0) + d)).sqrt();
            // `clamp(−s, s)`, the order of `f64::clamp` (`w` itself unless
            // beyond a bound).
            let clamp = |w: R| R::select(w.lt(-s), -s, R::select(w.gt(s), s, w));
            let (w0, w1) = (clamp(w0), clamp(w1));
            let length = w0 + w1;
            // `atan2(c, d² − w0 w1)`: `c = d (w0 + w1)` is its first part.
            let c = d * length;
            let x = d * d - w0 * w1;
            let (num, den, swap, regular) = angle::reduce(c, x);
            let theta = angle::core(num, den, swap, x, c);
            let (rho, one_minus_rho2) = rho_of(d, w0, w1, s);
            let thin = thin_value(theta, c.abs() / rho, rho, one_minus_rho2);
            let value = R::select(theta.abs().lt(k(1.0)), thin, theta - c);
            // `d = 0`: each endpoint's angle from the perpendicular is ±π/2
            // (0 at the centre itself).
            let half_turns = |w: R| R::select(w.eq(k(0.0)), k(0.0), k(0.5) * k(1.0).copysign(w));
            let at_centre = d.eq(k(0.0));
            let value = R::select(
                at_centre,
                sign * (half_turns(w0) + half_turns(w1)) * k(0.5),
                sign * value / k(2.0 * PI),
            );
            // In range: `|d| < 1`, a chord of nonzero length, and `d = 0` or
            // `d ≥ SAFE_LO` (no rescaling, one `atan2`) with a regular
            // angle and `ρ > 0`.
            let valid = finite
                & d.lt(k(1.0))
                & !length.eq(k(0.0))
                & (at_centre | (d.ge(k(SAFE_LO)) & regular & rho.gt(k(0.0))));
            R::select(valid, value, k(<$T>::NAN))
        }

        #[cfg(test)]
        mod tests {
            use super::*;

            /// Uniform values in `[0, 1)` from a 64-bit LCG seeded with
            /// `state`.
            fn uniform(mut state: u64) -> impl FnMut() -> $T {
                move || {
                    state = state
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    (state >> 11) as $T / (1u64 << 53) as $T
                }
            }

            /// The branch-free occlusion, compiled for the build's target
            /// (the form a processor without AVX2 runs), gives
            /// `circle_segment_occlusion`'s bits wherever it does not leave
            /// the edge to the scalar path, and leaves exactly the edges
            /// outside its range (`tests/disk.rs` checks the public entry).
            #[test]
            fn branch_free_occlusion_is_the_scalar_kernel() {
                let mut unit = uniform(0x2545_f491_4f6c_dd1d);
                let mut edges: Vec<($T, $T, $T)> = (0..4001)
                    .map(|i| {
                        let d = [0.3, 0.9, 0.999, 1e-3][i % 4] * (2.0 * unit() - 1.0);
                        let w = [0.5, 1.0, 3.0][i % 3];
                        (d, w * (2.0 * unit() - 1.0), w * (2.0 * unit() - 1.0))
                    })
                    .collect();
                edges.extend([
                    (0.0, 1.0, 1.0),
                    (-0.0, 0.0, 1.0),
                    (0.0, -0.5, 0.0),
                    (<$T>::NAN, 0.5, 0.5),
                    (0.5, 0.25, -0.25),
                    (1.0, 0.0, 0.0),
                    (SAFE_LO / 2.0, 0.5, 0.5),
                ]);
                let mut out = vec![0.0; edges.len()];
                assert!(occlusions_branch_free(&edges, &mut out));
                let mut vector = 0;
                for (&(d, w0, w1), &got) in edges.iter().zip(&out) {
                    let want = circle_segment_occlusion(d, w0, w1);
                    let s = ((1.0 - d.abs()) * (1.0 + d.abs())).max(0.0).sqrt();
                    let length = w0.clamp(-s, s) + w1.clamp(-s, s);
                    let in_range = d.is_finite()
                        && (d == 0.0 || (SAFE_LO..1.0).contains(&d.abs()))
                        && length != 0.0;
                    assert_eq!(got.is_nan(), !in_range, "d={d} w0={w0} w1={w1}");
                    if !got.is_nan() {
                        assert_eq!(got.to_bits(), want.to_bits(), "d={d} w0={w0} w1={w1}");
                        vector += 1;
                    }
                }
                assert!(vector >= 3000, "{vector} edges on the vector path");
            }

            /// Both forms of the branch-free loop — products by FMA and by
            /// Dekker's split — give `segment_disk_area`'s bits on edges of
            /// every kind (inside, crossing, outside, tangent, degenerate,
            /// out of range), whichever one the processor's dispatch picks.
            /// (`tests/disk.rs` checks the public entry on stiff edges.)
            #[test]
            fn both_branch_free_forms_are_the_scalar_kernel() {
                let mut unit = uniform(0x9e37_79b9_7f4a_7c15);
                let mut edges: Vec<($V2, $V2)> = (0..997)
                    .map(|i| {
                        // Boxes from well inside the unit disk to far outside.
                        let s = [0.5, 1.0, 2.0, 8.0, 1e3][i % 5];
                        let mut p = || $V2::new(s * (2.0 * unit() - 1.0), s * (2.0 * unit() - 1.0));
                        (p(), p())
                    })
                    .collect();
                let p = $V2::new(0.25, -1.5);
                edges.extend([
                    (p, p),
                    (p, -p),
                    ($V2::ZERO, p),
                    ($V2::new(1.0, -1.0), $V2::new(1.0, 1.0)),
                    ($V2::new(1.0, 0.0), $V2::new(0.0, 1.0)),
                    ($V2::new(<$T>::NAN, 0.0), p),
                    (p, $V2::new(<$T>::INFINITY, 0.0)),
                    ($V2::new(-2.0 * SAFE_HI, 0.5), $V2::new(2.0 * SAFE_HI, 0.5)),
                ]);
                for r in [1.0, 0.75] {
                    let mut out = vec![0.0; edges.len()];
                    let marked = areas_branch_free::<false>(r, &edges, &mut out);
                    let mut fused = vec![0.0; edges.len()];
                    let marked_fused = areas_branch_free::<true>(r, &edges, &mut fused);
                    assert!(marked && marked_fused, "the non-finite edges are marked");
                    for (i, &(a, b)) in edges.iter().enumerate() {
                        let want = segment_disk_area(r, a, b);
                        for got in [out[i], fused[i]] {
                            assert!(
                                got.to_bits() == want.to_bits() || got.is_nan(),
                                "r={r} a={a} b={b}: {got} vs {want}"
                            );
                        }
                        // Only edges outside the safe range are left to the
                        // scalar path.
                        let far = a.abs().max_element().max(b.abs().max_element());
                        let in_range = a.is_finite() && b.is_finite() && far <= SAFE_HI;
                        assert_eq!(out[i].is_nan(), !in_range, "a={a} b={b}");
                    }
                }
            }
        }
    };
}

/// `f64` disk-occlusion kernels.
pub mod f64 {
    disk_kernels!(f64, DVec2, 1.0e-60, 1.0e60);
}

/// `f32` disk-occlusion kernels.
pub mod f32 {
    disk_kernels!(f32, Vec2, 1.0e-6, 1.0e6);
}
