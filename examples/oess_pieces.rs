//! OESS against the exact reference, PCSS, 4-sample Monte Carlo and the
//! hard shadow on the segment-light scene, with the receivers split by how
//! the light looks from them: hidden, whole, one visible piece touching an
//! end (where OESS's model — one occluding edge per end — holds), one
//! piece inside the light, two or more pieces. The pieces are counted
//! exactly: the complement, in `[0, 1]`, of the union of the intervals
//! each triangle hides (`SegmentView::blocked`, the exact reference's own
//! intervals).
//!
//! `cargo run --release --example oess_pieces [SIDE]` prints a Markdown
//! table (receivers of the scene's camera at SIDE × SIDE, default 256, the
//! report's frames).

use softshadow::kernel::receiver_view::SegmentView;
use softshadow::method::{self, parse, Exact, Method};
use softshadow::render::{Frame, Stages};
use softshadow::scene::{builtin, Light};

/// How a receiver sees the light.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pieces {
    None,
    Whole,
    OneAtEnd,
    OneInside,
    Several,
}

const GROUPS: [(Pieces, &str); 5] = [
    (
        Pieces::OneAtEnd,
        "one piece touching an end (the model's case)",
    ),
    (Pieces::OneInside, "one piece inside the light"),
    (Pieces::Several, "two or more pieces"),
    (Pieces::None, "no piece (umbra)"),
    (Pieces::Whole, "the whole light"),
];

/// The visible pieces of `[0, 1]` outside the union of `blocked`.
fn pieces(mut blocked: Vec<(f64, f64)>) -> Pieces {
    blocked.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut visible = Vec::new();
    let mut reach = 0.0f64;
    for (s0, s1) in blocked {
        if s0 > reach {
            visible.push((reach, s0));
        }
        reach = reach.max(s1);
    }
    if reach < 1.0 {
        visible.push((reach, 1.0));
    }
    match visible.as_slice() {
        [] => Pieces::None,
        [(0.0, 1.0)] => Pieces::Whole,
        [(s0, s1)] if *s0 == 0.0 || *s1 == 1.0 => Pieces::OneAtEnd,
        [_] => Pieces::OneInside,
        _ => Pieces::Several,
    }
}

fn main() {
    let side: u32 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(256);
    let scene = builtin("linear-light").expect("the built-in segment-light scene");
    let Light::Segment(segment) = *scene.light() else {
        panic!("linear-light has a segment light");
    };
    let stages = Stages::new(&scene);
    let camera = scene
        .camera()
        .expect("a camera")
        .with_resolution(side, side)
        .expect("a valid side");
    let frame = Frame::from_camera(&camera, stages.bvh());
    let triangles = stages.bvh().occluders().triangles();
    let kinds: Vec<Pieces> = frame
        .receivers()
        .iter()
        .map(|r| {
            SegmentView::new(r.position, segment.a(), segment.b()).map_or(Pieces::Whole, |v| {
                pieces(triangles.iter().filter_map(|t| v.blocked(t)).collect())
            })
        })
        .collect();
    let exact = method::run(&Exact, &stages, &frame)
        .expect("exact")
        .output
        .visibility;
    let names = ["oess", "oess:depth-check", "pcss", "mc:4", "hard"];
    let values: Vec<Vec<f64>> = names
        .iter()
        .map(|n| {
            let m: Box<dyn Method> = parse(n).expect("a registry name");
            method::run(m.as_ref(), &stages, &frame)
                .expect("runs")
                .output
                .visibility
        })
        .collect();
    println!(
        "`linear-light`, {} receivers of the camera at {side}×{side}; RMSE of `V` against `Exact` per group (`cargo run --release --example oess_pieces {side}`).\n",
        exact.len()
    );
    let header: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    println!("| receivers | count | {} |", header.join(" | "));
    println!("|---|---:|{}", "---:|".repeat(names.len()));
    for (kind, label) in GROUPS {
        let idx: Vec<usize> = (0..exact.len()).filter(|&i| kinds[i] == kind).collect();
        let rmse = |v: &[f64]| {
            let sum: f64 = idx.iter().map(|&i| (v[i] - exact[i]).powi(2)).sum();
            (sum / idx.len().max(1) as f64).sqrt()
        };
        let cells: Vec<String> = values.iter().map(|v| format!("{:.4}", rmse(v))).collect();
        println!("| {label} | {} | {} |", idx.len(), cells.join(" | "));
    }
}
