//! The worked example of `docs/validate.md`, end to end, with a small
//! independent implementation standing in for "your renderer": it reads
//! `gbuffer`'s arrays with its own `.npy` code, ray-casts hard shadows
//! toward the light's centre with its own ray–triangle test over the
//! scene's triangles, writes its V buffer as `.npy` with its own writer,
//! and checks that `score`'s RMSE over the G-buffer equals the RMSE it
//! computes itself against `exact.npy`.

use softshadow::glam::DVec3;
use softshadow::scene::builtin;
use std::path::Path;

#[path = "support/cli.rs"]
mod cli_support;

use cli_support::softshadow;

/// The commands of the worked example, as `docs/validate.md` prints them.
const GBUFFER: &str = "softshadow gbuffer --scene default --width 160 --height 120 --out gb";
const SCORE: &str =
    "softshadow score --scene default --gbuffer gb --image hard.npy --out score --max-rmse 0.2";

/// A little-endian, C-order `.npy` (format 1.0) read by hand: the dtype
/// descriptor, the shape and the raw data bytes.
fn npy(path: &Path) -> (String, Vec<usize>, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
    assert_eq!((10 + len) % 64, 0, "the data is 64-byte aligned");
    assert!(header.contains("'fortran_order': False"), "{header}");
    let field = |key: &str| {
        let at = header.find(key).unwrap() + key.len();
        header[at..].trim_start_matches([':', ' ']).to_owned()
    };
    let descr = field("'descr'")[1..4].to_owned();
    let shape_text = field("'shape'");
    let shape = shape_text[1..shape_text.find(')').unwrap()]
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().unwrap())
        .collect();
    (descr, shape, bytes[10 + len..].to_vec())
}

fn f64s(data: &[u8]) -> Vec<f64> {
    data.chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// An `.npy` of `float64` written by hand.
fn write_npy(path: &Path, shape: &[usize], data: &[f64]) {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let mut header = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}{}), }}",
        dims.join(", "),
        if dims.len() == 1 { "," } else { "" }
    );
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header.as_bytes());
    for x in data {
        out.extend(x.to_le_bytes());
    }
    std::fs::write(path, out).unwrap();
}

/// Whether the open segment from `p` to `q` meets the triangle `t`
/// (Möller–Trumbore, the segment's ends excluded by a relative margin).
fn blocks(p: DVec3, q: DVec3, t: [DVec3; 3]) -> bool {
    let d = q - p;
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let h = d.cross(e2);
    let a = e1.dot(h);
    if a.abs() < 1e-300 {
        return false;
    }
    let s = p - t[0];
    let u = s.dot(h) / a;
    if !(0.0..=1.0).contains(&u) {
        return false;
    }
    let qv = s.cross(e1);
    let v = d.dot(qv) / a;
    if v < 0.0 || u + v > 1.0 {
        return false;
    }
    let tt = e2.dot(qv) / a;
    tt > 1e-9 && tt < 1.0 - 1e-9
}

#[test]
fn the_worked_example_scores_an_independent_hard_shadow_renderer() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/validate.md"))
        .expect("docs/validate.md");
    for command in [GBUFFER, SCORE] {
        assert!(doc.contains(command), "docs/validate.md lacks `{command}`");
    }
    let d = cli_support::dir("validate", "worked");
    let run = |command: &str| {
        let args: Vec<String> = command
            .split_whitespace()
            .skip(1)
            .enumerate()
            .map(|(k, a)| match a {
                "gb" | "score" | "hard.npy" if k > 0 => d.join(a).to_string_lossy().into_owned(),
                a => a.to_owned(),
            })
            .collect();
        softshadow(&args.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let out = run(GBUFFER);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // "Your renderer": the G-buffer in, hard shadows out.
    let gb = d.join("gb");
    let (descr, shape, pos) = npy(&gb.join("position.npy"));
    assert_eq!(
        (descr.as_str(), shape.as_slice()),
        ("<f8", &[120, 160, 3][..])
    );
    let (descr, _, obj) = npy(&gb.join("object.npy"));
    assert_eq!(descr, "<i4");
    let objects: Vec<i32> = obj
        .chunks_exact(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let (_, _, exact) = npy(&gb.join("exact.npy"));
    let exact = f64s(&exact);
    let pos = f64s(&pos);
    let camera: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(gb.join("camera.json")).unwrap()).unwrap();
    let c = &camera["light"]["center"];
    let light = DVec3::new(
        c[0].as_f64().unwrap(),
        c[1].as_f64().unwrap(),
        c[2].as_f64().unwrap(),
    );
    let scene = builtin("default").unwrap();
    let triangles: Vec<[DVec3; 3]> = scene
        .meshes()
        .iter()
        .flat_map(|m| {
            m.triangles()
                .iter()
                .map(|t| t.map(|i| m.positions()[i as usize]))
        })
        .collect();
    let mut hard = vec![f64::NAN; objects.len()];
    let (mut sum, mut count, mut lit, mut dark) = (0.0, 0usize, 0, 0);
    for k in 0..objects.len() {
        if objects[k] < 0 {
            continue;
        }
        let p = DVec3::from_slice(&pos[3 * k..3 * k + 3]);
        let v = if triangles.iter().any(|&t| blocks(p, light, t)) {
            dark += 1;
            0.0
        } else {
            lit += 1;
            1.0
        };
        hard[k] = v;
        sum += (v - exact[k]) * (v - exact[k]);
        count += 1;
    }
    assert!(lit > 1000 && dark > 300, "lit {lit}, in shadow {dark}");
    let own_rmse = (sum / count as f64).sqrt();
    write_npy(&d.join("hard.npy"), &[120, 160], &hard);

    let out = run(SCORE);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("| V | penumbra |"), "{stdout}");
    assert!(d.join("score").join("score-error.png").is_file());
    assert!(d.join("score").join("score-histogram.svg").is_file());
    let json = run(&format!("{SCORE} --json"));
    let s: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(s["pixels"].as_u64(), Some(count as u64));
    assert_eq!(s["nan_pixels"].as_u64(), Some(0));
    let rmse = s["rmse"].as_f64().unwrap();
    assert!(
        (rmse - own_rmse).abs() <= 1e-12,
        "score's RMSE {rmse}, the independent one {own_rmse}"
    );
    // Hard shadows are far from exact under a sphere light of radius ½.
    assert!(rmse > 0.02, "{rmse}");
    // The gate: the same image fails a tighter bound with status 3.
    let tight = run(&SCORE.replace("--max-rmse 0.2", &format!("--max-rmse {}", rmse * 0.99)));
    assert_eq!(tight.status.code(), Some(3));
    let err = String::from_utf8_lossy(&tight.stderr);
    assert!(err.contains("over --max-rmse"), "{err}");
}
