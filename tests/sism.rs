//! Soft irregular shadow mapping against independent answers: the exact
//! reference (where the paper's model is exact, to rounding; elsewhere
//! within the paper's approximations), the chain identities of the
//! composition, and the overdraw optimisations' bookkeeping.

use softshadow::arbitrary::Rng;
use softshadow::definitions::in_penumbra;
use softshadow::glam::DVec3;
use softshadow::kernel::silhouette::MeshTopology;
use softshadow::kernel::wedge::f64::PenumbraWedge;
use softshadow::method::sism::{Bound, Composition, EdgeSource, SismPasses};
use softshadow::method::{self, MethodError, Sism};
use softshadow::render::{Frame, Receiver, Stages};
use softshadow::scene::builtin::floor_receivers;
use softshadow::scene::primitive::{cuboid, quad, sphere, Transform};
use softshadow::scene::{builtin, Light, Scene};

fn floor_frame(scene: &Scene, side: usize) -> Frame {
    Frame::from_receivers(
        floor_receivers(scene, side)
            .into_iter()
            .map(|p| Receiver {
                position: p,
                normal: Some(DVec3::Y),
                object: Some(0),
            })
            .collect(),
    )
}

fn passes(m: &Sism, scene: &Scene, frame: &Frame) -> SismPasses {
    let stages = Stages::new(scene);
    let input = method::check(m, &stages, frame).expect("a valid frame");
    m.passes(&input).expect("sism runs")
}

fn exact(scene: &Scene, frame: &Frame) -> Vec<f64> {
    let stages = Stages::new(scene);
    method::run(&method::Exact, &stages, frame)
        .expect("exact runs")
        .output
        .visibility
}

struct Errors {
    rmse: f64,
    max: f64,
    mean_signed: f64,
}

fn errors(v: &[f64], reference: &[f64], keep: impl Fn(usize) -> bool) -> Errors {
    let e: Vec<f64> = (0..v.len())
        .filter(|&i| keep(i))
        .map(|i| v[i] - reference[i])
        .collect();
    let n = e.len().max(1) as f64;
    Errors {
        rmse: (e.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
        max: e.iter().fold(0.0f64, |m, x| m.max(x.abs())),
        mean_signed: e.iter().sum::<f64>() / n,
    }
}

/// A disk light facing down over horizontal plates: each plate is at one
/// depth of the disk-aligned light frame, so the footprint radius is exact,
/// and the per-edge decomposition of eq. 3 plus the umbra's winding is
/// Green's theorem: SISM is exact up to rounding for one plate, and with
/// the exact composition for overlapping plates too.
fn plates(heights_and_offsets: &[(f64, f64)]) -> Scene {
    let mut scene = Scene::new(Light::disk(DVec3::new(0.0, 4.0, 0.0), -DVec3::Y, 0.6).unwrap())
        .with_mesh(
            "floor",
            quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap(),
        );
    for (k, &(h, dx)) in heights_and_offsets.iter().enumerate() {
        scene = scene.with_mesh(
            format!("plate{k}"),
            quad(DVec3::new(dx, h, 0.1), DVec3::X * 0.4, -DVec3::Z * 0.3).unwrap(),
        );
    }
    scene
}

// Both sides compute the same areas, SISM by eq. 3 edge by edge, the exact
// reference by an arrangement; each is accurate to a few ulps of the
// light's area, far below 1e-9.
const ROUNDING: f64 = 1e-9;

#[test]
fn one_plate_under_a_disk_light_is_exact() {
    let scene = plates(&[(1.0, 0.0)]);
    let frame = floor_frame(&scene, 48);
    let reference = exact(&scene, &frame);
    let penumbra = reference.iter().filter(|&&v| in_penumbra(v)).count();
    assert!(penumbra > 300, "the grid covers the penumbra ({penumbra})");
    for composition in [Composition::Independent, Composition::ExactUnion] {
        let m = Sism::default().with_composition(composition);
        let p = passes(&m, &scene, &frame);
        let e = errors(&p.visibility, &reference, |_| true);
        assert!(e.max < ROUNDING, "{composition:?}: max error {}", e.max);
    }
}

#[test]
fn overlapping_plates_bias_darker_and_the_exact_union_removes_it() {
    // Two plates at 0.8 and 1.6, offset so that their shadows half overlap.
    let scene = plates(&[(0.8, -0.2), (1.6, 0.2)]);
    let frame = floor_frame(&scene, 48);
    let reference = exact(&scene, &frame);
    let independent = passes(&Sism::default(), &scene, &frame);
    let union = passes(
        &Sism::default().with_composition(Composition::ExactUnion),
        &scene,
        &frame,
    );
    // Where both plates cover part of the footprint and the light is not
    // fully blocked, C = 0 adds their overlap twice: too dark, never too
    // bright (each plate's own term is exact here).
    let overlap = |i: usize| independent.evaluations[i] >= 2 && reference[i] > 0.0;
    let count = (0..reference.len()).filter(|&i| overlap(i)).count();
    assert!(count > 50, "overlapping penumbrae sampled ({count})");
    let before = errors(&independent.visibility, &reference, overlap);
    for (i, (v, r)) in independent.visibility.iter().zip(&reference).enumerate() {
        assert!(*v <= r + ROUNDING, "receiver {i}");
    }
    assert!(
        before.mean_signed < -0.01,
        "C = 0 is biased darker: {}",
        before.mean_signed
    );
    // The exact composition: each plate is at one depth, so the union of
    // their scaled images is exactly the receiver view.
    let after = errors(&union.visibility, &reference, |_| true);
    assert!(after.max < ROUNDING, "exact union: max error {}", after.max);
}

#[test]
fn an_isolated_convex_occluder_has_rmse_below_one_percent() {
    // Random slabs and balls over a plane under a random sphere light: the
    // paper's approximations (one point of projection, one depth per edge)
    // are small here; the claim to check is RMSE < 0.01 against Exact.
    // (A cube is not such a case: its side faces, nearly edge-on from the
    // light's centre, become front-facing from part of the light and move
    // the silhouette — §5.1's hidden silhouettes; measured RMSE up to
    // 0.015 on this generator's cube cases.)
    let mut rng = Rng::new(0x5151_0001);
    for case in 0..12 {
        let h = rng.uniform(0.6, 1.4);
        let size = rng.uniform(0.15, 0.4);
        let occluder = if case % 2 == 0 {
            let t = Transform::new(1.0, rng.uniform(0.0, 90.0), DVec3::new(0.0, h, 0.0)).unwrap();
            let half = DVec3::new(size, 0.01, size * 0.7);
            t.apply(&cuboid(-half, half).unwrap()).unwrap()
        } else {
            sphere(DVec3::new(0.0, h, 0.0), size, 48).unwrap()
        };
        let light = Light::sphere(
            DVec3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(3.0, 4.5),
                rng.uniform(-1.0, 1.0),
            ),
            rng.uniform(0.1, 0.5),
        )
        .unwrap();
        let scene = Scene::new(light)
            .with_mesh(
                "floor",
                quad(DVec3::ZERO, DVec3::X * 4.0, -DVec3::Z * 4.0).unwrap(),
            )
            .with_mesh("occluder", occluder);
        let frame = floor_frame(&scene, 40);
        let reference = exact(&scene, &frame);
        let p = passes(&Sism::default(), &scene, &frame);
        let e = errors(&p.visibility, &reference, |_| true);
        assert!(
            e.rmse < 0.01,
            "case {case}: RMSE {} (max {})",
            e.rmse,
            e.max
        );
    }
}

#[test]
fn all_edges_give_the_silhouettes_buffer() {
    for name in [
        "default",
        "overlapping-penumbrae",
        "comb",
        "depth-complexity",
    ] {
        let scene = builtin(name).unwrap();
        let frame = floor_frame(&scene, 48);
        for composition in [Composition::Independent, Composition::ExactUnion] {
            let sil = passes(
                &Sism::default().with_composition(composition),
                &scene,
                &frame,
            );
            let all = passes(
                &Sism::default()
                    .with_composition(composition)
                    .with_edges(EdgeSource::AllEdges),
                &scene,
                &frame,
            );
            // Interior edges cancel pairwise: each term is ≤ 1 and rounded
            // to a few ulps, and a receiver sees at most a few hundred.
            let worst = sil
                .visibility
                .iter()
                .zip(&all.visibility)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(worst < 1e-10, "{name} {composition:?}: {worst}");
            assert_eq!(sil.umbra, all.umbra, "{name}: the umbra pass is shared");
            let (e_sil, e_all): (u64, u64) = (
                sil.evaluations.iter().map(|&x| u64::from(x)).sum(),
                all.evaluations.iter().map(|&x| u64::from(x)).sum(),
            );
            assert!(e_all > e_sil, "{name}: every edge costs more");
        }
    }
}

#[test]
fn overdraw_optimisations_change_no_value_only_the_work() {
    for name in ["default", "overlapping-penumbrae", "large-light"] {
        let scene = builtin(name).unwrap();
        let frame = floor_frame(&scene, 64);
        let run = |bin_depth: bool, wedge_column: bool, bound: Bound| {
            let stages = Stages::new(&scene);
            let m = Sism::default()
                .with_optimisations(bin_depth, wedge_column)
                .with_bound(bound);
            let input = method::check(&m, &stages, &frame).unwrap();
            let p = m.passes(&input).unwrap();
            let stats = stages.stats();
            (p, stats)
        };
        let (base, s0) = run(false, false, Bound::Paper);
        let (bin, s1) = run(true, false, Bound::Paper);
        let (both, s2) = run(true, true, Bound::Paper);
        let (cons, s3) = run(true, true, Bound::Conservative);
        for (label, p) in [("bin", &bin), ("bin+wedge", &both), ("conservative", &cons)] {
            assert_eq!(p.visibility, base.visibility, "{name} {label}");
        }
        let evals = |s: &softshadow::render::Stats| s.counter("sism edge-receiver evaluations");
        let bin_saved = s1.counter("sism evaluations saved by bin depth");
        let wedge_saved = s2.counter("sism evaluations saved by wedge column");
        assert_eq!(
            evals(&s0),
            evals(&s1) + bin_saved,
            "{name}: bin depth bookkeeping"
        );
        assert_eq!(
            evals(&s1),
            evals(&s2) + wedge_saved,
            "{name}: wedge column bookkeeping"
        );
        assert!(wedge_saved > 0, "{name}: the wedge column saves work");
        assert!(evals(&s3) > 0);
    }
}

#[test]
fn umbra_reads_zero_and_outside_every_wedge_is_the_umbra_pass() {
    for name in ["default", "contact", "comb"] {
        let scene = builtin(name).unwrap();
        let frame = floor_frame(&scene, 64);
        let reference = exact(&scene, &frame);
        let p = passes(&Sism::default(), &scene, &frame);
        let Light::Sphere(sphere) = *scene.light() else {
            panic!("sphere light");
        };
        let (center, radius) = (sphere.center(), sphere.radius());
        // The kernel's conservative wedges of every edge that can be a
        // silhouette from some point of the light: outside all of them the
        // light is entirely blocked or entirely visible.
        let mut wedges = Vec::new();
        for mesh in scene.meshes() {
            let topo = MeshTopology::new(mesh.triangles(), mesh.positions().len()).unwrap();
            for e in topo
                .potential_silhouettes(mesh.positions(), center, radius)
                .unwrap()
            {
                let [a, b] = topo.edges()[e as usize].map(|v| mesh.positions()[v as usize]);
                wedges.push(PenumbraWedge::new(a, b, center, radius).unwrap());
            }
        }
        let (mut outside, mut dark) = (0, 0);
        for (i, r) in frame.receivers().iter().enumerate() {
            if wedges.iter().any(|w| w.contains(r.position)) {
                continue;
            }
            outside += 1;
            // The paper's footprint lies inside the wedge: every edge term
            // evaluated here (the quad is coarser than the wedge) is 0.
            assert_eq!(p.occlusion[i], p.umbra[i], "{name}: receiver {i}");
            assert_eq!(
                p.visibility[i],
                (1.0 - p.umbra[i]).clamp(0.0, 1.0),
                "{name}: receiver {i}"
            );
            // Outside every wedge the light is all blocked or all visible:
            // SISM reads exactly 0 or 1, the exact reference that to its
            // rounding (`1 − area/area`, a few ulps).
            assert!(
                p.visibility[i] == 0.0 || p.visibility[i] == 1.0,
                "{name} {i} umbra {} ref {} at {:?}",
                p.umbra[i],
                reference[i],
                frame.receivers()[i].position
            );
            assert!(
                (p.visibility[i] - reference[i]).abs() < 1e-12,
                "{name}: receiver {i}: {} against {}",
                p.visibility[i],
                reference[i]
            );
            if p.visibility[i] == 0.0 {
                dark += 1;
            }
        }
        assert!(
            outside > 100 && dark > 10,
            "{name}: {outside} outside, {dark} in umbra"
        );
    }
}

#[test]
fn names_round_trip_and_unsupported_lights_are_errors() {
    for name in [
        "sism",
        "sism:all-edges",
        "sism:exact-union,conservative,no-bin-depth,no-wedge-column",
        "sism:cells=2,bin=8,slices=4",
    ] {
        let m = method::parse(name).unwrap();
        assert_eq!(m.name(), name);
    }
    assert!(method::parse("sism:sideways").is_err());
    assert!(method::parse("sismx").is_err());
    for light in [
        Light::segment(DVec3::new(-1.0, 3.0, 0.0), DVec3::new(1.0, 3.0, 0.0)).unwrap(),
        Light::point(DVec3::new(0.0, 3.0, 0.0)).unwrap(),
        Light::rect(DVec3::new(0.0, 3.0, 0.0), DVec3::X, DVec3::Z).unwrap(),
    ] {
        let scene = Scene::new(light).with_mesh(
            "plate",
            quad(DVec3::Y, DVec3::X * 0.5, DVec3::Z * 0.5).unwrap(),
        );
        let stages = Stages::new(&scene);
        let frame = Frame::from_receivers(vec![Receiver {
            position: DVec3::ZERO,
            normal: None,
            object: None,
        }]);
        assert!(matches!(
            method::run(&Sism::default(), &stages, &frame),
            Err(MethodError::UnsupportedLight { .. })
        ));
    }
}

#[test]
fn degenerate_frames_give_values_or_errors_never_nan() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let m = Sism::default();
    // No receiver.
    let empty = Frame::from_receivers(Vec::new());
    let run = |frame: &Frame| method::run(&m, &stages, frame).map(|r| r.output);
    assert_eq!(run(&empty).unwrap().visibility.len(), 0);
    // One receiver, behind the light's plane, coincident receivers, a far one.
    let c = scene.light().center();
    let at = |p: DVec3| Receiver {
        position: p,
        normal: None,
        object: None,
    };
    let frame = Frame::from_receivers(vec![
        at(c + DVec3::Y * 2.0),
        at(DVec3::new(0.1, 0.0, 0.1)),
        at(DVec3::new(0.1, 0.0, 0.1)),
        at(DVec3::new(1e6, 0.0, 0.0)),
    ]);
    let v = run(&frame).unwrap().visibility;
    assert!(v.iter().all(|x| (0.0..=1.0).contains(x)));
    assert_eq!(v[0], 1.0, "behind the light: outside the light view");
    assert_eq!(v[1], v[2]);
    // Inside the sphere light: an error naming the receiver.
    let inside = Frame::from_receivers(vec![at(DVec3::ZERO), at(c)]);
    assert!(matches!(
        run(&inside),
        Err(MethodError::Receiver { index: 1, .. })
    ));
    // Invalid options.
    let bad = Sism::default().with_grid(1.0, 16, 0);
    assert!(matches!(
        method::run(&bad, &stages, &frame),
        Err(MethodError::InvalidOption { .. })
    ));
}

#[test]
fn values_do_not_depend_on_the_number_of_threads() {
    let scene = builtin("default").unwrap();
    let frame = floor_frame(&scene, 48);
    for m in [
        Sism::default(),
        Sism::default().with_composition(Composition::ExactUnion),
    ] {
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| passes(&m, &scene, &frame))
        };
        assert_eq!(run(1), run(3), "{m:?}");
    }
}

#[test]
fn a_solid_stored_as_a_triangle_soup_is_welded_and_reads_as_the_solid() {
    // The same box, indexed and as a soup of unshared corners: the
    // topology stage welds bit-identical corners, so the box stays one
    // closed component and both give the same buffer — before the weld the
    // soup counted every layer twice (penumbra errors near 0.5).
    let light = Light::disk(DVec3::new(0.0, 4.0, 0.0), -DVec3::Y, 0.6).unwrap();
    let solid = cuboid(DVec3::new(-0.4, 0.8, -0.3), DVec3::new(0.4, 1.2, 0.3)).unwrap();
    let corners: Vec<DVec3> = solid
        .triangles()
        .iter()
        .flat_map(|t| t.map(|i| solid.positions()[i as usize]))
        .collect();
    let soup_triangles = (0..solid.triangles().len() as u32)
        .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    let soup = softshadow::scene::Mesh::new(corners, soup_triangles).unwrap();
    let floor = quad(DVec3::ZERO, DVec3::X * 3.0, -DVec3::Z * 3.0).unwrap();
    let indexed = Scene::new(light)
        .with_mesh("floor", floor.clone())
        .with_mesh("box", solid);
    let unwelded = Scene::new(light)
        .with_mesh("floor", floor)
        .with_mesh("box", soup);
    let frame = floor_frame(&indexed, 48);
    let a = passes(&Sism::default(), &indexed, &frame).visibility;
    let b = passes(&Sism::default(), &unwelded, &frame).visibility;
    let reference = exact(&indexed, &frame);
    let penumbra = |i: usize| reference[i] > 0.0 && reference[i] < 1.0;
    assert!((0..a.len()).filter(|&i| penumbra(i)).count() > 200);
    for i in 0..a.len() {
        assert!(
            (a[i] - b[i]).abs() < ROUNDING,
            "receiver {i}: {} vs {}",
            a[i],
            b[i]
        );
    }
    // The paper's model on a box: within its hidden-silhouette error.
    assert!(errors(&b, &reference, penumbra).rmse < 0.05);
}

#[test]
fn the_largest_grid_options_stay_within_the_key_budget_and_change_no_value() {
    // 1024-cell bins and 256 slices over a handful of receivers would pad
    // to 2²⁸ keys without the budget; the grid lowers them instead.
    let scene = plates(&[(1.0, 0.0)]);
    let frame = floor_frame(&scene, 3);
    let big = Sism::default().with_grid(64.0, 1024, 256);
    let a = passes(&big, &scene, &frame).visibility;
    let b = passes(&Sism::default(), &scene, &frame).visibility;
    assert_eq!(a, b);
}
