//! The peak-memory estimate of a run and `--max-memory`: a run whose
//! estimate exceeds the limit is refused before anything is allocated.

use softshadow::method::Method;

pub(crate) fn parse_gib(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(g) if g.is_finite() && g > 0.0 => Ok(g),
        _ => Err(format!("expected a positive number of GiB, got {s:?}")),
    }
}

/// Measured peak memory of `render` (`/usr/bin/time -f %M`, 1024² and
/// 2048², hard, exact, sism, oess): 103–117 bytes per pixel over a fixed
/// part (the BVH, the scene, the default maps of SISM and OESS) of at most
/// about 130 MiB. A method's own maps at other resolutions
/// ([`Method::map_bytes`]) are counted apart.
const BYTES_PER_PIXEL: f64 = 120.0;
const FIXED_BYTES: f64 = 256.0 * MIB;
const MIB: f64 = (1u64 << 20) as f64;
const GIB: f64 = (1u64 << 30) as f64;

/// Half of the machine's memory (`/proc/meminfo`), or 8 GiB when unknown.
fn default_memory_limit() -> f64 {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        t.lines()
            .find(|l| l.starts_with("MemTotal:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<f64>().ok())
            .map(|kb| kb * 1024.0)
    });
    total.map_or(8.0 * GIB, |b| 0.5 * b)
}

/// Refuses, before any allocation, a run of `method` on `receivers`
/// receivers (`what` names them: `--width W --height H`, a points file)
/// whose estimated peak — per receiver, fixed, and the method's maps —
/// exceeds the limit (`--max-memory` GiB, else half the machine's memory).
pub(crate) fn check_memory(
    what: &str,
    receivers: u64,
    method: &dyn Method,
    max_gib: Option<f64>,
) -> Result<(), String> {
    let maps = method.map_bytes() as f64;
    let estimate = BYTES_PER_PIXEL * receivers as f64 + FIXED_BYTES + maps;
    let (limit, whence) = match max_gib {
        Some(g) => (g * GIB, "--max-memory"),
        None => (
            default_memory_limit(),
            "half this machine's memory; --max-memory to change",
        ),
    };
    if estimate > limit {
        let maps = if maps > 0.0 {
            format!(", {:.1} GiB of the method's maps", maps / GIB)
        } else {
            String::new()
        };
        return Err(format!(
            "{what}: about {:.1} GiB estimated ({BYTES_PER_PIXEL} bytes per receiver, \
             {:.0} MiB fixed{maps}), over the limit of {:.1} GiB ({whence})",
            estimate / GIB,
            FIXED_BYTES / MIB,
            limit / GIB
        ));
    }
    Ok(())
}
