//! What each paper reports of its own speed, for the report's paper table:
//! scene, triangles, resolution, hardware, frame rate — read from the
//! papers, flattened tables reconstructed by the order of their values
//! and checked by arithmetic (the papers give no error figures).

/// One configuration a paper reports.
pub(crate) struct PaperRow {
    /// The method's registry name.
    pub method: &'static str,
    /// The paper.
    pub paper: &'static str,
    /// Scene and triangle count.
    pub scene: &'static str,
    /// Screen and map resolution.
    pub resolution: &'static str,
    /// The hardware.
    pub hardware: &'static str,
    /// What the paper reports of its speed.
    pub speed: &'static str,
    /// Our closest built-in scene.
    pub ours: &'static str,
}

pub(crate) const PAPERS: &[PaperRow] = &[
    PaperRow {
        method: "single-sample",
        paper: "Brabec & Seidel 2002",
        scene: "torus over a plane (Fig. 7); triangles not given",
        resolution: "512² screen, 256² light depth/ID map",
        hardware: "Pentium 4 1.7 GHz (shadows on the CPU), GeForce3",
        speed: "10–15 fps soft (30 fps hard only), r_max = 20",
        ours: "default",
    },
    PaperRow {
        method: "sism",
        paper: "Johnson et al. 2009",
        scene: "Fern, 212k triangles (13k silhouette edges)",
        resolution: "800×600, light samples = eye pixels",
        hardware: "simulated Larrabee, 24 cores at 1 GHz",
        speed: "15 fps (soft-shadow kernel 55.0 ms)",
        ours: "default",
    },
    PaperRow {
        method: "sism",
        paper: "Johnson et al. 2009",
        scene: "Saloon (Call of Juarez), 60k triangles",
        resolution: "1600×1200",
        hardware: "simulated Larrabee, 24 cores at 1 GHz",
        speed: "33 fps (27 fps on Street, 155k)",
        ours: "depth-complexity",
    },
    PaperRow {
        method: "ssoc",
        paper: "Mo, Popescu & Wyman 2007",
        scene: "Bunny, 70k triangles",
        resolution: "512² screen; map size not given",
        hardware: "GeForce 8800 GTX, 3.2 GHz Pentium 4 Xeon",
        speed: "85.4 fps (silhouettes 8.0 ms on the CPU, shadow map 0.8, SSOC 1.7, eye 8.2)",
        ours: "default",
    },
    PaperRow {
        method: "ssoc",
        paper: "Mo, Popescu & Wyman 2007",
        scene: "Two teapots, 13k triangles",
        resolution: "512² screen",
        hardware: "GeForce 8800 GTX",
        speed: "186.6 fps",
        ours: "overlapping-penumbrae",
    },
    PaperRow {
        method: "backprojected-ssoc",
        paper: "Mo & Wyman 2007 (sketch)",
        scene: "—",
        resolution: "—",
        hardware: "—",
        speed: "no figures (\"interactive\")",
        ours: "default",
    },
    PaperRow {
        method: "oess",
        paper: "Reimann & Dreier 2016",
        scene: "everyday objects (Fig. 8); triangles not given",
        resolution: "endpoint maps up to 2000²; screen not given",
        hardware: "Radeon HD 7950",
        speed: "60 fps (a frame-rate cap; 30 fps at 2000²); GPU load only",
        ours: "linear-light",
    },
];
