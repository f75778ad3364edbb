//! OESS against the exact reference, PCSS, 4-sample Monte Carlo and the
//! hard shadow on the segment-light scene, with the receivers split by how
//! the exact reference sees the light from them
//! (`softshadow::kernel::receiver_view::Pieces`): one visible piece
//! touching an end (where OESS's model — one occluding edge per end —
//! holds), one piece inside the light, two or more pieces, none, the whole
//! light. The groups and errors are the report's (`output::score::PIECES`,
//! `pieces_masks`, `group_errors`): `softshadow report --scene
//! linear-light` writes the same table for every setting; this is the
//! quick way to it for five.
//!
//! `cargo run --release --example oess_pieces [SIDE]` prints a Markdown
//! table (receivers of the scene's camera at SIDE × SIDE, default 256, the
//! report's frames).

use softshadow::method::{self, parse, Exact, Method};
use softshadow::output::score::{group_errors, pieces_masks, PIECES};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;

fn main() {
    let side: u32 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(256);
    let scene = builtin("linear-light").expect("the built-in segment-light scene");
    let stages = Stages::new(&scene);
    let camera = scene
        .camera()
        .expect("a camera")
        .with_resolution(side, side)
        .expect("a valid side");
    let frame = Frame::from_camera(&camera, stages.bvh());
    let masks = pieces_masks(stages.bvh(), scene.light(), frame.receivers())
        .expect("linear-light has a segment light");
    let exact = method::run(&Exact, &stages, &frame)
        .expect("exact")
        .output
        .visibility;
    let names = ["oess", "oess:depth-check", "pcss", "mc:4", "hard"];
    let errors: Vec<_> = names
        .iter()
        .map(|n| {
            let m: Box<dyn Method> = parse(n).expect("a registry name");
            let v = method::run(m.as_ref(), &stages, &frame)
                .expect("runs")
                .output
                .visibility;
            group_errors(&v, &exact, &masks, |_| true)
        })
        .collect();
    println!(
        "`linear-light`, {} receivers of the camera at {side}×{side}; RMSE of `V` against `Exact` per group (`cargo run --release --example oess_pieces {side}`).\n",
        exact.len()
    );
    let header: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    println!("| receivers | count | {} |", header.join(" | "));
    println!("|---|---:|{}", "---:|".repeat(names.len()));
    for (g, label) in PIECES.iter().enumerate() {
        let count = masks[g].iter().filter(|x| **x).count();
        let cells: Vec<String> = errors.iter().map(|e| format!("{:.4}", e[g].rmse)).collect();
        println!("| {label} | {count} | {} |", cells.join(" | "));
    }
}
