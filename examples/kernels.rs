//! Using the kernels from code: the visibility of a disk light seen past a
//! triangle, the way the exact reference and SISM compose them.
//!
//! `cargo run --example kernels`

use softshadow::glam::{DVec2, DVec3};
use softshadow::kernel::disk::f64::{circle_segment_occlusion, polygon_disk_area};
use softshadow::kernel::predicate::{orient2d, Sign};
use softshadow::kernel::silhouette::MeshTopology;
use softshadow::kernel::wedge::f64::{penumbra_quad, QuadBound};
use std::f64::consts::PI;

fn main() {
    // The receiver view (docs/definitions.md): the light is a disk of radius R at
    // the origin of its plane; an occluding triangle, already clipped and
    // projected onto that plane from the receiver, is a polygon.
    let radius = 0.5;
    let triangle = [
        DVec2::new(-0.2, -1.0),
        DVec2::new(1.5, -0.3),
        DVec2::new(0.1, 1.2),
    ];
    // The kernel takes either orientation; orient it counter-clockwise so the
    // covered area comes out positive.
    let ccw = if orient2d(triangle[0], triangle[1], triangle[2]) == Sign::Negative {
        [triangle[0], triangle[2], triangle[1]]
    } else {
        triangle
    };
    let covered = polygon_disk_area(radius, &ccw);
    let visibility = 1.0 - covered / (PI * radius * radius);
    println!(
        "triangle covers {covered:.6} of the light's {:.6}: V = {visibility:.6}",
        PI * radius * radius
    );

    // SISM's per-edge view of the same question (Johnson et al. eq. 3): one
    // straight silhouette edge at distance d from the receiver's footprint
    // centre, in units of the footprint radius, occludes the minor circular
    // segment beyond it — positive outside the hard shadow, negative inside.
    for d in [0.9, 0.5, 0.0, -0.5] {
        let half_chord = (1.0f64 - d * d).sqrt();
        let occlusion = circle_segment_occlusion(d, half_chord, half_chord);
        println!("edge at d = {d:+.1}: signed occlusion {occlusion:+.6}");
    }

    // The edges those views start from: the silhouette of a mesh seen from
    // the light's centre, each oriented with its front face on the left.
    let positions = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(0.0, 0.0, -1.0),
    ];
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let light = DVec3::new(0.0, 0.0, -4.0);
    match MeshTopology::new(&faces, positions.len())
        .map_err(|e| e.to_string())
        .and_then(|mesh| {
            mesh.silhouettes_from_point(&positions, light)
                .map_err(|e| e.to_string())
        }) {
        Ok(edges) => {
            for e in &edges {
                println!(
                    "silhouette edge {} -> {} (multiplicity {})",
                    e.from, e.to, e.multiplicity
                );
            }
        }
        Err(e) => println!("no silhouettes: {e}"),
    }

    // SISM's coarse test for one of them: the light-image-plane rectangle
    // holding every receiver (down to depth 12) whose view of a light of
    // radius 0.3 the edge can cross. Coordinates are in the light frame
    // (origin at the light's centre, +z toward the scene).
    let (e0, e1) = (positions[0] - light, positions[2] - light);
    match penumbra_quad(e0, e1, 0.3, 12.0) {
        Ok(QuadBound::Quad(q)) => println!(
            "penumbra quad: half-width {:.4} around the projected edge, bound {:?} – {:?}",
            q.half_width, q.min, q.max
        ),
        other => println!("penumbra quad: {other:?}"),
    }
}
