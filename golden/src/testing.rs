//! Test helpers shared by every test in the workspace (feature `testing`, which brings in
//! `proptest`; enable it from `[dev-dependencies]`, never from a crate's normal dependencies).
//!
//! Seeded, reproducible property-test runners: each prints its seed; set `SHADECORE_SEED=<u64>`
//! to replay a run (or to explore with other seeds). Without it the seed is derived from the
//! test's name ([`seed_for`]), so CI is deterministic. Also: random rotations and
//! [`split_vertices`] for the scene and raster tests.

use glam::DQuat;
use proptest::prelude::{prop, Strategy};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::scene::Mesh;

/// Re-exported from [`crate::seed`] (always compiled) so tests find it beside [`runner`].
pub use crate::seed::seed_for;

/// A proptest runner with `cases` cases, seeded by [`seed_for`]; prints the seed.
pub fn runner(name: &str, cases: u32) -> TestRunner {
    let seed = seed_for(name);
    println!("[{name}] seed {seed} (replay with SHADECORE_SEED={seed})");
    with_seed(seed, cases)
}

/// A runner seeded with `seed` exactly as [`runner`] seeds its runners (for stimulus drawn
/// from strategies with a seed of the caller's).
pub fn seeded_runner(seed: u64) -> TestRunner {
    with_seed(seed, Config::default().cases)
}

fn with_seed(seed: u64, cases: u32) -> TestRunner {
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes))
}

/// Uniformly random rotations: four components uniform in the cube, rejected outside the unit
/// ball (uniform on directions, no Box–Muller needed) or too short to normalize.
pub fn quaternion() -> impl Strategy<Value = DQuat> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("outside the unit ball or too short", |q| {
            (1e-6..=1.0).contains(&q.iter().map(|c| c * c).sum::<f64>())
        })
        .prop_map(|q| DQuat::from_xyzw(q[0], q[1], q[2], q[3]).normalize())
}

/// The same mesh with every triangle given its own three vertices (bit-identical positions and
/// normals), as an OBJ exporter that splits every vertex writes it: the scene code must treat
/// it exactly like the shared mesh (no crack between the copies).
pub fn split_vertices(m: &Mesh) -> Mesh {
    let mut out = Mesh::default();
    for t in &m.triangles {
        let base = out.positions.len() as u32;
        for &i in t {
            out.positions.push(m.positions[i as usize]);
            out.normals.push(m.normals[i as usize]);
        }
        out.triangles.push([base, base + 1, base + 2]);
    }
    out.uvs = m.uvs.clone();
    out
}

/// One named test case of `named_triangles.txt`: triangles walked back to back, and their
/// vertex intensities (`values[triangle][vertex][channel]`) where the case gives them.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedCase {
    pub name: &'static str,
    pub tris: Vec<[(i32, i32); 3]>,
    pub values: Option<Vec<[[f64; 3]; 3]>>,
}

/// The named triangles shared by the raster, address-block and intensity-interpolator tests
/// (`golden/src/named_triangles.txt`: shapes, tiny and degenerate cases, slivers, address
/// limits, back-to-back runs), in file order.
pub fn named_triangles() -> Vec<NamedCase> {
    fn numbers<T: std::str::FromStr>(s: &str, line: &str) -> Vec<T> {
        s.split_whitespace()
            .map(|w| {
                w.parse()
                    .unwrap_or_else(|_| panic!("named_triangles.txt: {line:?}"))
            })
            .collect()
    }
    fn groups<T: std::str::FromStr + Copy, const N: usize>(s: &str, line: &str) -> Vec<[T; N]> {
        s.split(';')
            .map(|g| {
                let v: Vec<T> = numbers(g, line);
                <[T; N]>::try_from(v).unwrap_or_else(|_| panic!("named_triangles.txt: {line:?}"))
            })
            .collect()
    }
    include_str!("named_triangles.txt")
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|line| {
            let (name, rest) = line.split_once(':').expect("name: coordinates");
            let (coords, values) = match rest.split_once('|') {
                Some((c, v)) => (c, Some(v)),
                None => (rest, None),
            };
            let tris = groups::<i32, 6>(coords, line)
                .into_iter()
                .map(|c| [(c[0], c[1]), (c[2], c[3]), (c[4], c[5])])
                .collect::<Vec<_>>();
            let values = values.map(|v| {
                groups::<f64, 9>(v, line)
                    .into_iter()
                    .map(|c| [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]])
                    .collect::<Vec<_>>()
            });
            assert!(
                values.as_ref().is_none_or(|v| v.len() == tris.len()),
                "{line:?}"
            );
            NamedCase {
                name: name.trim(),
                tris,
                values,
            }
        })
        .collect()
}

/// The named cases whose name starts with `prefix`, each with its triangles.
pub fn named_with_prefix(prefix: &str) -> Vec<[(i32, i32); 3]> {
    named_triangles()
        .into_iter()
        .filter(|c| c.name.starts_with(prefix))
        .flat_map(|c| c.tris)
        .collect()
}

/// xorshift64*: seeded stimulus without proptest's machinery, for benches that draw many
/// plain numbers (seed it with a test's seed; 0 is made odd).
pub struct Rng(pub u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in 0..n.
    pub fn below(&mut self, n: i32) -> i32 {
        (self.next_u64() % n as u64) as i32
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}
