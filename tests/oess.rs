//! Occluding edges soft shadows against independent answers: one straight
//! edge of a half-plane occluder — across the light, skew to it and along
//! it — has a closed-form visible fraction, which the exact reference
//! agrees with and OESS meets within what moving the edge by one map texel
//! changes; the paper's eq. 1 agrees with the stable construction; and the
//! paper's three artifacts show where the paper says they appear.

use softshadow::glam::{DVec2, DVec3};
use softshadow::method::{self, Exact, Oess};
use softshadow::render::{Frame, Receiver, Stages};
use softshadow::scene::primitive::{cuboid, quad, sphere};
use softshadow::scene::{builtin, Light, Scene};

/// The segment light of every scene here: `L = (−1.2, 2.5, 0)`, `R = (1.2,
/// 2.5, 0)`.
const L: DVec3 = DVec3::new(-1.2, 2.5, 0.0);
const R: DVec3 = DVec3::new(1.2, 2.5, 0.0);
/// The half-plane occluder's height.
const H: f64 = 1.0;
/// The floor's half side.
const FLOOR: f64 = 3.0;

/// A half-plane occluder at height `H`: the points of `y = H` with
/// `n · (x, z) > c`, `n` a unit vector of the xz-plane.
#[derive(Clone, Copy, Debug)]
struct HalfPlane {
    n: DVec2,
    c: f64,
}

impl HalfPlane {
    /// The visible fraction of the light from the floor point `f`, in
    /// closed form: the ray from `f` to `X(s) = L + s(R − L)` crosses `y =
    /// H` at `P(s) = f + (H / (2.5 − f.y))(X(s) − f)`, and `n·P(s)` is
    /// affine in `s`, so the hidden part is the `s` where it exceeds `c`.
    fn fraction(&self, f: DVec3) -> f64 {
        let t = H / (2.5 - f.y);
        let g = |s: f64| {
            let p = f + (L + (R - L) * s - f) * t;
            self.n.dot(DVec2::new(p.x, p.z))
        };
        let (g0, g1) = (g(0.0), g(1.0) - g(0.0));
        if g1 == 0.0 {
            return if g0 > self.c { 0.0 } else { 1.0 };
        }
        // Visible where g0 + g1·s ≤ c.
        let s = (self.c - g0) / g1;
        if g1 > 0.0 {
            s.clamp(0.0, 1.0)
        } else {
            1.0 - s.clamp(0.0, 1.0)
        }
    }

    /// The occluder as a mesh: a 16 × 8 rectangle at height `H` beyond the
    /// edge (its far sides are well off the floor's shadows), over a
    /// floor of side `2·FLOOR`.
    fn scene(&self) -> Scene {
        let along = DVec2::new(-self.n.y, self.n.x);
        let centre = self.n * (self.c + 4.0);
        // `quad` takes the centre and two half sides.
        let plate = quad(
            DVec3::new(centre.x, H, centre.y),
            DVec3::new(along.x, 0.0, along.y) * 8.0,
            DVec3::new(self.n.x, 0.0, self.n.y) * 4.0,
        )
        .unwrap();
        Scene::new(Light::segment(L, R).unwrap())
            .with_mesh(
                "floor",
                quad(DVec3::ZERO, DVec3::X * FLOOR, -DVec3::Z * FLOOR).unwrap(),
            )
            .with_mesh("plate", plate)
    }
}

fn floor_frame(points: impl Iterator<Item = (f64, f64)>) -> Frame {
    Frame::from_receivers(
        points
            .map(|(x, z)| Receiver {
                position: DVec3::new(x, 1e-9, z),
                normal: Some(DVec3::Y),
                object: Some(0),
            })
            .collect(),
    )
}

/// The size of one endpoint-map texel, in world units at depth `depth`,
/// along x and along z, for `n × n` maps: the maps share one window, the
/// union of both ends' fits over the receivers and the occluder vertices,
/// `extent / (n − 2)` per texel (`LightView::fit`). Both ends' frames have
/// `x` along the light and look straight down here (the scene's centre is
/// below the light's), so a point's image coordinates from an end `e` are
/// `((p − e).x, (p − e).z) / (e.y − p.y)` up to the sign of the second.
fn texel(stages: &Stages, frame: &Frame, n: u32, depth: f64) -> DVec2 {
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let points = frame.receivers().iter().map(|r| r.position).chain(
        stages
            .bvh()
            .occluders()
            .triangles()
            .iter()
            .flatten()
            .copied(),
    );
    for p in points {
        for e in [L, R] {
            let u = DVec2::new(p.x - e.x, p.z - e.z) / (e.y - p.y);
            lo = lo.min(u);
            hi = hi.max(u);
        }
    }
    (hi - lo) / f64::from(n - 2) * depth
}

/// `(V, reached)` of OESS with `map`-texel maps.
fn oess(m: &Oess, stages: &Stages, frame: &Frame) -> (Vec<f64>, Vec<[bool; 2]>) {
    let input = method::check(m, stages, frame).unwrap();
    let p = m.passes(&input).unwrap();
    (p.visibility, p.reached)
}

/// Checks one half-plane: the exact reference against the closed form, and
/// OESS within the closed form of the edge moved by one texel either way.
/// Returns the largest error of OESS and the number of receivers in the
/// penumbra.
fn check_edge(edge: HalfPlane, points: &[(f64, f64)]) -> (f64, usize) {
    let scene = edge.scene();
    let stages = Stages::new(&scene);
    let frame = floor_frame(points.iter().copied());
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let m = Oess::default();
    let (v, reached) = oess(&m, &stages, &frame);
    // Moving the edge by one texel at its depth moves `c` by at most
    // |n_x|·Δx + |n_z|·Δz.
    let t = texel(&stages, &frame, m.resolution, 2.5 - H);
    let dc = edge.n.x.abs() * t.x + edge.n.y.abs() * t.y;
    let (mut worst, mut penumbra) = (0.0f64, 0);
    for (i, r) in frame.receivers().iter().enumerate() {
        let f = r.position;
        let want = edge.fraction(f);
        // The receivers sit 1e-9 above the floor and the exact reference
        // offsets them along the normal: the fraction moves by far less
        // than 1e-7.
        assert!(
            (exact[i] - want).abs() < 1e-7,
            "exact {} vs closed form {want} at {f}",
            exact[i]
        );
        let moved = [-dc, dc].map(|d| {
            HalfPlane {
                c: edge.c + d,
                ..edge
            }
            .fraction(f)
        });
        let (lo, hi) = (moved[0].min(moved[1]), moved[0].max(moved[1]));
        assert!(
            v[i] >= lo - 1e-12 && v[i] <= hi + 1e-12,
            "{edge:?} at {f}: OESS {} outside [{lo}, {hi}] (closed form {want}, reached {:?})",
            v[i],
            reached[i]
        );
        if want > 0.0 && want < 1.0 {
            penumbra += 1;
        }
        worst = worst.max((v[i] - want).abs());
    }
    (worst, penumbra)
}

/// A grid of floor points over `x ∈ [x0, x1]`, `z ∈ [z0, z1]`.
fn grid(x: (f64, f64), z: (f64, f64), n: u32) -> Vec<(f64, f64)> {
    let at = |(a, b): (f64, f64), k: u32| a + (b - a) * f64::from(k) / f64::from(n - 1);
    (0..n)
        .flat_map(|i| (0..n).map(move |j| (at(x, i), at(z, j))))
        .collect()
}

#[test]
fn an_edge_across_the_light_is_the_closed_form_within_a_texel() {
    // The edge along z at x = 0, the plate over x > 0: the penumbra on the
    // floor is x ∈ [−0.8, 0.8] (from L: 1.2·H/1.5; from R likewise).
    let edge = HalfPlane {
        n: DVec2::X,
        c: 0.0,
    };
    let (worst, penumbra) = check_edge(edge, &grid((-1.0, 1.0), (-0.8, 0.8), 41));
    assert!(penumbra > 1000, "{penumbra} receivers in the penumbra");
    println!("across: largest error {worst:.2e} over {penumbra} penumbra receivers");
}

#[test]
fn a_skew_edge_is_the_closed_form_within_a_texel() {
    // The edge at 45° to the light (and to the map's rows).
    for angle in [45.0f64, 120.0] {
        let a = angle.to_radians();
        let edge = HalfPlane {
            n: DVec2::new(a.sin(), -a.cos()),
            c: 0.1,
        };
        let (worst, penumbra) = check_edge(edge, &grid((-1.2, 1.2), (-0.8, 0.8), 41));
        assert!(penumbra > 500, "{angle}°: {penumbra} in the penumbra");
        println!("{angle}°: largest error {worst:.2e} over {penumbra} penumbra receivers");
    }
}

#[test]
fn an_edge_along_the_light_casts_a_hard_shadow() {
    // Parallel to the light, the edge hides all of it or none of it from
    // every point: V is 0 or 1, and OESS's answer is a texel row's.
    let edge = HalfPlane {
        n: DVec2::Y,
        c: 0.2,
    };
    let (worst, penumbra) = check_edge(edge, &grid((-1.0, 1.0), (0.0, 0.7), 41));
    assert_eq!(penumbra, 0);
    println!("along: largest error {worst:.2e}");
}

#[test]
fn the_law_of_sines_agrees_with_the_stable_construction() {
    // Wherever eq. 1 is defined the two constructions are one formula;
    // elsewhere the stable one is used. On the linear-light scene the
    // largest difference is rounding (measured 2e-15), far below 1e-9.
    let scene = builtin("linear-light").unwrap();
    let stages = Stages::new(&scene);
    let camera = scene.camera().unwrap().with_resolution(160, 160).unwrap();
    let frame = Frame::from_camera(&camera, stages.bvh());
    let (stable, reached) = oess(&Oess::default(), &stages, &frame);
    let (sines, _) = oess(&Oess::default().with_law_of_sines(true), &stages, &frame);
    let mut compared = 0;
    for i in 0..stable.len() {
        assert!(stable[i].is_finite() && sines[i].is_finite());
        assert!(
            (stable[i] - sines[i]).abs() < 1e-9,
            "receiver {i}: stable {} law of sines {}",
            stable[i],
            sines[i]
        );
        compared += usize::from(reached[i] != [false, false]);
    }
    assert!(compared > 1000, "{compared} receivers reached by an edge");
}

/// A floor, and the meshes given, under the segment light.
fn scene_with(meshes: Vec<(&str, softshadow::scene::Mesh)>) -> Scene {
    let mut scene = Scene::new(Light::segment(L, R).unwrap()).with_mesh(
        "floor",
        quad(DVec3::ZERO, DVec3::X * FLOOR, -DVec3::Z * FLOOR).unwrap(),
    );
    for (name, mesh) in meshes {
        scene = scene.with_mesh(name, mesh);
    }
    scene
}

#[test]
fn object_alternation() {
    // The paper's §6: a sphere and a pillar; where the sphere's cross-
    // section in the map rows ends, the occluding edge leaps from the
    // sphere to the pillar and the shadow changes abruptly. Here a wall
    // across the light stands on the floor right of a floating ball; on a
    // floor line along z through the penumbra both cast, the rows through
    // the ball take its edge and the rows past it the wall's.
    let scene = scene_with(vec![
        (
            "wall",
            cuboid(DVec3::new(0.5, 0.0, -1.0), DVec3::new(0.7, 1.2, 1.0)).unwrap(),
        ),
        ("ball", sphere(DVec3::new(0.0, 0.7, 0.0), 0.35, 32).unwrap()),
    ]);
    let stages = Stages::new(&scene);
    let zs: Vec<f64> = (0..=200).map(|k| 0.005 * f64::from(k)).collect();
    let frame = floor_frame(zs.iter().map(|&z| (-0.1, z)));
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let (v, _) = oess(&Oess::default(), &stages, &frame);
    // Over 0.01 along z (about 1.3 map rows here), how much more OESS
    // changes than the exact answer: the leap of the edge from the ball to
    // the wall.
    let (excess, at) = (0..zs.len() - 2)
        .map(|i| ((v[i + 2] - v[i]).abs() - (exact[i + 2] - exact[i]).abs(), i))
        .fold((f64::NEG_INFINITY, 0), |a, b| if b.0 > a.0 { b } else { a });
    println!(
        "object alternation: at z = {:.3} OESS goes {:.3} → {:.3}, the exact answer {:.3} → {:.3}",
        zs[at],
        v[at],
        v[at + 2],
        exact[at],
        exact[at + 2]
    );
    // Where the ball's cross-section ends: its shadow on this line ends
    // near z = 0.35·2.5/1.8 ≈ 0.49.
    assert!(
        (0.4..0.55).contains(&zs[at]),
        "the leap is at z = {}",
        zs[at]
    );
    assert!(
        excess > 0.15,
        "OESS changes only {excess} more than the exact answer"
    );
}

/// The root mean square of `v` minus its running mean over `±half`
/// neighbours: what varies faster than that window.
fn ripple(v: &[f64], half: usize) -> f64 {
    let n = v.len() - 2 * half;
    let sum: f64 = (half..v.len() - half)
        .map(|i| {
            let mean = v[i - half..=i + half].iter().sum::<f64>() / (2 * half + 1) as f64;
            (v[i] - mean).powi(2)
        })
        .sum();
    (sum / n as f64).sqrt()
}

#[test]
fn spare_edge_interpolation() {
    // The paper's §6: the occluding edges are texel centres, a rasterized
    // silhouette, and interpolating between two rows leaves stripes in the
    // penumbra. Across the rows of a skew straight edge's penumbra the
    // error ripples from row to row; the ripple is the texel's, so it
    // halves when the maps' texels do.
    let a = 45f64.to_radians();
    let edge = HalfPlane {
        n: DVec2::new(a.sin(), -a.cos()),
        c: 0.1,
    };
    let scene = edge.scene();
    let stages = Stages::new(&scene);
    let zs: Vec<f64> = (0..=600).map(|k| -0.3 + 0.001 * f64::from(k)).collect();
    // Along a line that stays in the penumbra's middle: the edge's shadow
    // runs at 45° on the floor too.
    let frame = floor_frame(zs.iter().map(|&z| (z + 0.15, z)));
    let want: Vec<f64> = frame
        .receivers()
        .iter()
        .map(|r| edge.fraction(r.position))
        .collect();
    assert!(
        want.iter().all(|&w| w > 0.05 && w < 0.95),
        "the line leaves the penumbra"
    );
    let mut ripples = Vec::new();
    for map in [400, 800, 1600] {
        let (v, _) = oess(&Oess::default().with_resolution(map), &stages, &frame);
        let error: Vec<f64> = v.iter().zip(&want).map(|(a, b)| a - b).collect();
        // A window of ±2 map rows on the floor (depth 2.5).
        let row = texel(&stages, &frame, map, 2.5).y;
        let half = (2.0 * row / 0.001).round() as usize;
        ripples.push((map, ripple(&error, half), ripple(&want, half)));
    }
    println!(
        "spare edge interpolation: (map, ripple of the error, of the exact answer) {ripples:?}"
    );
    for w in ripples.windows(2) {
        let ratio = w[0].1 / w[1].1;
        assert!(
            (1.4..2.9).contains(&ratio),
            "{} → {}: ripple ratio {ratio}",
            w[0].0,
            w[1].0
        );
    }
    for (map, error, exact) in ripples {
        assert!(error > 10.0 * exact, "{map}: ripple {error} vs {exact}");
    }
}

#[test]
fn receiver_penetration() {
    // The paper's §6 and substep 4.1: every receiver whose texel an
    // outreach reached is penumbra, whatever its depth, so receivers
    // beyond the surface the map sees, in absolute umbra, are lit. Here a
    // box stands on the floor left of the light's middle; its face toward
    // +z is turned away from the light (umbra), and from L it lies behind
    // the box's left face, which the outreach from the box's rim covers.
    // With `depth-check` (the paper's first approach) it is umbra again.
    let scene = scene_with(vec![(
        "box",
        cuboid(DVec3::new(-0.9, 0.0, -0.3), DVec3::new(-0.5, 0.5, 0.1)).unwrap(),
    )]);
    let stages = Stages::new(&scene);
    let frame = Frame::from_receivers(
        grid((-0.88, -0.52), (0.02, 0.48), 21)
            .into_iter()
            .map(|(x, y)| Receiver {
                position: DVec3::new(x, y, 0.1),
                normal: Some(DVec3::Z),
                object: Some(1),
            })
            .collect(),
    );
    let exact = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    // Umbra up to the exact reference's rounding.
    assert!(
        exact.iter().all(|&v| v < 1e-12),
        "the face is umbra: {exact:?}"
    );
    let (v, reached) = oess(&Oess::default(), &stages, &frame);
    let penetrated = reached.iter().filter(|r| r[0] || r[1]).count();
    let lit = v.iter().filter(|&&v| v > 0.0).count();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    println!(
        "receiver penetration: {penetrated} of {} umbra receivers reached, {lit} lit, mean V {mean:.3}",
        v.len()
    );
    assert!(lit * 4 > v.len() && mean > 0.05);
    let (checked, reached) = oess(&Oess::default().with_depth_check(true), &stages, &frame);
    assert!(
        reached.iter().all(|r| !r[0] && !r[1]),
        "no penumbra with the depth check"
    );
    let mean_checked = checked.iter().sum::<f64>() / checked.len() as f64;
    println!("with depth-check: mean V {mean_checked:.3}");
    assert!(mean_checked < 0.25 * mean);
    // What stays lit is the shadow maps' own error at a silhouette: a
    // receiver whose ray from R passes within a texel of the box's corner
    // (those within 0.05 of the face's edge x = −0.5; a texel is about
    // 0.01 there) can fall in a texel of R's map that sees past the box,
    // and reads seen by R.
    for (i, r) in frame.receivers().iter().enumerate() {
        assert!(
            checked[i] == 0.0 || r.position.x > -0.55,
            "{} lit ({}) with the depth check",
            r.position,
            checked[i]
        );
    }
}

#[test]
fn end_weights_shade_on_the_plain_picture_s_scale() {
    use softshadow::output::image::{shaded, shaded_by_ends};
    let scene = builtin("linear-light").unwrap();
    let stages = Stages::new(&scene);
    let camera = scene.camera().unwrap().with_resolution(48, 36).unwrap();
    let frame = Frame::from_camera(&camera, stages.bvh());
    let n = frame.receivers().len();
    // The light wholly visible: the picture is the plain one at V = 1.
    assert_eq!(
        shaded_by_ends(&scene, &frame, &vec![[0.5, 0.5]; n]).data,
        shaded(&scene, &frame, &vec![1.0; n]).data
    );
    // Half the light visible, at one end or the other: a receiver nearer
    // to L (x < 0, where L is at x = −1.2) is brighter with L's half.
    let left = shaded_by_ends(&scene, &frame, &vec![[0.5, 0.0]; n]);
    let right = shaded_by_ends(&scene, &frame, &vec![[0.0, 0.5]; n]);
    let mut compared = 0;
    for (pixel, &k) in frame.pixels().iter().enumerate() {
        let Some(r) = frame.receivers().get(k as usize) else {
            continue; // background
        };
        let (a, b) = (left.data[3 * pixel], right.data[3 * pixel]);
        if r.position.x < -0.3 && r.normal.is_some_and(|n| n.y > 0.9) {
            assert!(a >= b, "pixel {pixel}, receiver at {}", r.position);
            compared += usize::from(a > b);
        }
    }
    assert!(compared > 50, "{compared} receivers brighter from L's half");
}

/// A segment light of any length is OESS's to answer (issue 39: a length of
/// 1e-300 was refused, "no light frame", where the loader accepts it): down
/// to the least difference of doubles it gives the point light's answer,
/// the limit of a shrinking segment — 0 where the ray from the receiver to
/// the light crosses the card, 1 where it passes well clear. Lengths below
/// an ulp of ordinary coordinates need ends near 0: the segment runs from
/// `(0, 3, 0)` along a slanted direction of the xz-plane.
#[test]
fn a_segment_of_any_length_is_answered() {
    // The card: a triangle at y = 1, not symmetric about the light.
    let card = [
        DVec3::new(-1.1, 1.0, -0.9),
        DVec3::new(1.3, 1.0, -1.2),
        DVec3::new(0.1, 1.0, 1.4),
    ];
    let c = DVec3::new(0.0, 3.0, 0.0);
    let mesh = softshadow::scene::Mesh::new(card.to_vec(), vec![[0, 1, 2]]).unwrap();
    let floor = quad(DVec3::ZERO, DVec3::X * 4.0, DVec3::Z * 4.0).unwrap();
    // How far inside the card (negative: outside) the ray from the floor
    // point p to c crosses y = 1, by the edge functions (the card is
    // counter-clockwise in (x, z): inside is to the left of each edge).
    let inside = |p: DVec3| {
        let q = p + (c - p) * ((1.0 - p.y) / (c.y - p.y));
        let q = DVec2::new(q.x, q.z);
        (0..3)
            .map(|k| {
                let (a, b) = (card[k], card[(k + 1) % 3]);
                let (a, b) = (DVec2::new(a.x, a.z), DVec2::new(b.x, b.z));
                (b - a).normalize().perp_dot(q - a)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let frame = floor_frame(grid((-2.7, 2.7), (-2.7, 2.7), 41).into_iter());
    for length in [1e-6, 1e-40, 1e-160, 1e-300, 4.9e-324] {
        let b = c + DVec3::new(0.8 * length, 0.0, -0.6 * length);
        assert_ne!(b, c, "{length:e}");
        let light = Light::segment(c, b).unwrap();
        let scene = Scene::new(light)
            .with_mesh("floor", floor.clone())
            .with_mesh("card", mesh.clone());
        let stages = Stages::new(&scene);
        let run = method::run(&Oess::default(), &stages, &frame)
            .unwrap_or_else(|e| panic!("length {length:e}: {e}"));
        let mut checked = [0, 0];
        for (r, &v) in frame.receivers().iter().zip(&run.output.visibility) {
            let d = inside(r.position);
            // Five texels of the 800² maps over the floor's window and
            // more from the shadow's edge: the point light's answer.
            if d.abs() > 0.05 {
                let want = if d > 0.0 { 0.0 } else { 1.0 };
                assert_eq!(v, want, "length {length:e}, receiver {}", r.position);
                checked[usize::from(d > 0.0)] += 1;
            }
        }
        assert!(checked[0] > 500 && checked[1] > 200, "{checked:?}");
    }
}
