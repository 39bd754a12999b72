//! Reproducible seeds: [`seed_for`] derives a stable seed from a name, or takes `SHADECORE_SEED`.
//!
//! Plain `std` and always compiled (the CLI seeds its random stimulus with it); the proptest
//! runners built on it live in `golden::testing` (feature `testing`).

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
