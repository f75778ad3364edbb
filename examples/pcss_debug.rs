use softshadow::method::{self, Exact, HardShadow, Pcss};
use softshadow::render::{Frame, Stages};
use softshadow::scene::builtin;
fn main() {
    let scene = builtin("default").unwrap();
    let stages = Stages::new(&scene);
    let cam = scene.camera().unwrap().with_resolution(128, 128).unwrap();
    let frame = Frame::from_camera(&cam, stages.bvh());
    let ex = method::run(&Exact, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let res: u32 = std::env::args().nth(1).map_or(128, |s| s.parse().unwrap());
    let pc = method::run(
        &Pcss {
            resolution: res,
            ..Pcss::default()
        },
        &stages,
        &frame,
    )
    .unwrap()
    .output
    .visibility;
    let hd = method::run(&HardShadow, &stages, &frame)
        .unwrap()
        .output
        .visibility;
    let mut idx: Vec<usize> = (0..ex.len()).collect();
    idx.sort_by(|&a, &b| (pc[b] - ex[b]).abs().total_cmp(&(pc[a] - ex[a]).abs()));
    {
        let i = idx[0];
        let r = frame.receivers()[i];
        let maps = stages.light_maps(&frame, res, res);
        let fm = maps.as_ref().as_ref().unwrap();
        let view = &fm.view;
        let maps = &fm.maps;
        let lf = view.frame();
        let p = lf.to_light(r.position);
        let [ax, ay, az] = lf.axes();
        let n = r.normal.unwrap();
        let n = glam::DVec3::new(n.dot(ax), n.dot(ay), n.dot(az));
        let s = glam::DVec2::new(p.x / p.z, p.y / p.z);
        let t = view.to_pixel(s);
        println!("p {p} s {s} texel {t} n {n}");
        for dr in -2i32..=2 {
            let mut line = String::new();
            for dc in -2i32..=2 {
                let (c, rr) = (
                    (t.x.floor() as i32 + dc) as u32,
                    (t.y.floor() as i32 + dr) as u32,
                );
                let cc = view.pixel_center(c, rr);
                let zp = n.dot(p) / n.dot(glam::DVec3::new(cc.x, cc.y, 1.0));
                line += &format!(" {:.4}/{:.4}", maps.depth_at(c, rr), zp);
            }
            println!("{line}");
        }
    }
    for &i in idx.iter().take(15) {
        let r = frame.receivers()[i];
        println!(
            "{i} ex {:.3} pcss {:.3} hard {} obj {:?} p {:.3} n {:.2}",
            ex[i],
            pc[i],
            hd[i],
            r.object,
            r.position,
            r.normal.unwrap()
        );
    }
}
#[allow(dead_code)]
fn unused() {}
