//! The exact reference at depth, the figures in one program: the
//! pile of `n` random occluders over one receiver (exact against Monte
//! Carlo at 4096 samples), layers stacked `10⁻⁴` apart, and one convex
//! polygon given as a fan of slivers. Median of `runs` calls each.
//!
//! `UNION=auto|grid|tree cargo run --release --example union_depth -- [pile|stacked|fan|all] [runs]`,
//! or `... -- one CASE N CALLS` (see [`one`]).

#[path = "../benches/support/pile.rs"]
mod pile;
use pile::occluders;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::DVec3;
use softshadow::kernel::receiver_view::UnionSearch;
use softshadow::reference::exact::{self, Scratch};
use softshadow::reference::monte_carlo::{self, Options};
use softshadow::scene::Light;
use std::hint::black_box;
use std::time::Instant;

fn median(runs: usize, mut f: impl FnMut() -> f64) -> (f64, f64) {
    let mut times = Vec::new();
    let mut value = 0.0;
    for _ in 0..runs {
        let t = Instant::now();
        value = f();
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[runs / 2], value)
}

/// The fan of `n` slivers of case `case` (0: covering the light, the apex
/// in view; 1: covering it, the apex far out of view; 2: covering part),
/// its receiver and light.
fn fan(case: usize, n: usize) -> (Vec<[DVec3; 3]>, DVec3, Light) {
    let p = DVec3::new(0.0137, 0.0213, 0.0);
    let light = Light::disk(
        DVec3::new(0.1031, 0.2017, 4.0),
        DVec3::new(0.03, 0.01, 1.0),
        0.5,
    )
    .expect("a light");
    let (center, radius, apex) = [
        (
            DVec3::new(0.0, 0.0, 2.0),
            50.0,
            DVec3::new(0.0313, 0.0271, 2.0),
        ),
        (DVec3::new(0.0, 0.0, 2.0), 50.0, DVec3::new(30.3, 20.1, 2.0)),
        (
            DVec3::new(0.35, 0.2, 2.0),
            0.23,
            DVec3::new(0.3513, 0.1871, 2.0),
        ),
    ][case];
    let ring: Vec<DVec3> = (0..n)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / n as f64;
            center + DVec3::new(a.cos(), a.sin(), 0.0) * radius
        })
        .collect();
    let tris = (0..n).map(|k| [apex, ring[k], ring[(k + 1) % n]]).collect();
    (tris, p, light)
}

/// The `n` layers stacked `10⁻⁴` apart of `benches/references.rs`, their
/// receiver and light.
fn stacked(n: usize) -> (Vec<[DVec3; 3]>, DVec3, Light) {
    let t = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).expect("a light");
    let tris = (0..n)
        .map(|k| t.map(|v| v + DVec3::new(0.0, 1e-4 * k as f64, 0.0)))
        .collect();
    (tris, DVec3::new(0.9, 0.0, 0.0), light)
}

/// `union_depth one CASE N CALLS`: one case, its exact answer `CALLS`
/// times (for instruction counts: the difference between two counts of
/// calls is the answers' alone). CASE: `pile`, `mc` (Monte Carlo at 4096
/// samples on the pile), `stacked`, `fan0`, `fan1`, `fan2`.
fn one(args: &[String], scratch: &mut Scratch) {
    let case = args[2].as_str();
    let n: usize = args[3].parse().expect("N");
    let calls: usize = args[4].parse().expect("CALLS");
    let (tris, p, light) = match case {
        "pile" | "mc" => (
            occluders(n),
            DVec3::ZERO,
            Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5).expect("a light"),
        ),
        "stacked" => stacked(n),
        f => fan(f[3..].parse().expect("fan0, fan1 or fan2"), n),
    };
    let bvh = Bvh::new(Occluders::from_triangles(tris));
    let mut v = 0.0;
    for _ in 0..calls {
        v = if case == "mc" {
            monte_carlo::visibility(&bvh, &light, p, &Options::new(4096))
                .expect("a receiver")
                .visibility
        } else {
            exact::visibility_with(&bvh, &light, p, scratch).expect("a receiver")
        };
        black_box(v);
    }
    println!("{case} {n} x{calls}: V = {v:.17e}");
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let what = args.get(1).map_or("all", String::as_str);
    let runs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let mut scratch = Scratch::default();
    // UNION=auto (the default), grid or tree.
    match std::env::var("UNION").as_deref() {
        Ok("tree") => scratch.set_union_search(UnionSearch::Tree),
        Ok("grid") => scratch.set_union_search(UnionSearch::Grid),
        _ => scratch.set_union_search(UnionSearch::Auto),
    }
    if what == "one" {
        one(&args, &mut scratch);
        return;
    }
    if what == "pile" || what == "all" {
        let light = Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5).expect("a light");
        for n in [256, 1024, 4096, 16384] {
            let bvh = Bvh::new(Occluders::from_triangles(occluders(n)));
            let (t, v) = median(runs, || {
                black_box(exact::visibility_with(&bvh, &light, DVec3::ZERO, &mut scratch).unwrap())
            });
            let options = Options::new(4096);
            let (tm, _) = median(runs, || {
                black_box(monte_carlo::visibility(&bvh, &light, DVec3::ZERO, &options).unwrap())
                    .visibility
            });
            println!(
                "pile {n:6}: exact {:9.3} ms  mc4096 {:7.3} ms  ratio {:6.2}  V = {v:.17e}",
                t * 1e3,
                tm * 1e3,
                t / tm
            );
        }
    }
    let t = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    if what == "stacked" || what == "all" {
        let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).expect("a light");
        let p = DVec3::new(0.9, 0.0, 0.0);
        for n in [1_000usize, 10_000] {
            let stacked: Vec<[DVec3; 3]> = (0..n)
                .map(|k| t.map(|v| v + DVec3::new(0.0, 1e-4 * k as f64, 0.0)))
                .collect();
            let bvh = Bvh::new(Occluders::from_triangles(stacked));
            let r = if n > 1000 { runs.min(3) } else { runs };
            let (t, v) = median(r, || {
                black_box(exact::visibility_with(&bvh, &light, p, &mut scratch).unwrap())
            });
            println!("stacked {n:6}: exact {:9.3} ms  V = {v:.17e}", t * 1e3);
        }
    }
    if what == "fan" || what == "all" {
        let p = DVec3::new(0.0137, 0.0213, 0.0);
        let light = Light::disk(
            DVec3::new(0.1031, 0.2017, 4.0),
            DVec3::new(0.03, 0.01, 1.0),
            0.5,
        )
        .expect("a light");
        let cases = [
            (
                "apex in view",
                DVec3::new(0.0, 0.0, 2.0),
                50.0,
                DVec3::new(0.0313, 0.0271, 2.0),
            ),
            (
                "apex out",
                DVec3::new(0.0, 0.0, 2.0),
                50.0,
                DVec3::new(30.3, 20.1, 2.0),
            ),
            (
                "part",
                DVec3::new(0.35, 0.2, 2.0),
                0.23,
                DVec3::new(0.3513, 0.1871, 2.0),
            ),
        ];
        for (name, center, radius, apex) in cases {
            for n in [10_000usize, 100_000] {
                let ring: Vec<DVec3> = (0..n)
                    .map(|k| {
                        let a = k as f64 * std::f64::consts::TAU / n as f64;
                        center + DVec3::new(a.cos(), a.sin(), 0.0) * radius
                    })
                    .collect();
                let tris: Vec<[DVec3; 3]> =
                    (0..n).map(|k| [apex, ring[k], ring[(k + 1) % n]]).collect();
                let bvh = Bvh::new(Occluders::from_triangles(tris));
                let r = if n > 10_000 { runs.min(3) } else { runs };
                let (t, v) = median(r, || {
                    black_box(exact::visibility_with(&bvh, &light, p, &mut scratch).unwrap())
                });
                println!(
                    "fan {name:12} {n:6}: exact {:9.3} ms  V = {v:.17e}",
                    t * 1e3
                );
            }
        }
    }
}
