//! Using the kernels from code: the visibility of a disk light seen past a
//! triangle, the way the exact reference and SISM compose them.
//!
//! `cargo run --example kernels`

use glam::DVec2;
use softshadow::kernel::disk::f64::{circle_segment_occlusion, polygon_disk_area};
use softshadow::kernel::predicate::{orient2d, Sign};
use std::f64::consts::PI;

fn main() {
    // The receiver view (DESIGN.md §2): the light is a disk of radius R at
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
}
