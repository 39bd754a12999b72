//! Seeded, reproducible property-test runners shared by every test in the workspace.
//!
//! Each runner prints its seed; set `SHADECORE_SEED=<u64>` to replay a run (or to explore with
//! other seeds). Without it the seed is derived from the test's name, so CI is deterministic.

use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// The seed for `name`: `SHADECORE_SEED` if set, otherwise a stable hash of the name.
pub fn seed_for(name: &str) -> u64 {
    if let Ok(s) = std::env::var("SHADECORE_SEED") {
        if let Ok(v) = s.trim().parse::<u64>() {
            return v;
        }
        eprintln!("SHADECORE_SEED={s:?} is not a u64; using the default seed");
    }
    // FNV-1a: stable across Rust versions, unlike DefaultHasher.
    name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// A proptest runner with `cases` cases, seeded by [`seed_for`]; prints the seed.
pub fn runner(name: &str, cases: u32) -> TestRunner {
    let seed = seed_for(name);
    println!("[{name}] seed {seed} (replay with SHADECORE_SEED={seed})");
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes))
}

/// The same mesh with every triangle given its own three vertices (bit-identical positions and
/// normals), as an OBJ exporter that splits every vertex writes it: the scene code must treat
/// it exactly like the shared mesh (no crack between the copies).
pub fn split_vertices(m: &crate::scene::Mesh) -> crate::scene::Mesh {
    let mut out = crate::scene::Mesh::default();
    for t in &m.triangles {
        let base = out.positions.len() as u32;
        for &i in t {
            out.positions.push(m.positions[i as usize]);
            out.normals.push(m.normals[i as usize]);
        }
        out.triangles.push([base, base + 1, base + 2]);
    }
    out
}
