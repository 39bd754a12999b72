//! Where the lit front end loses the bits the 2-LSB bound needs (issue 9;
//! `docs/bump-precision.md` holds the tables and what they mean).
//!
//! `cargo run --release --example bump_precision` prints, for four scenes, how far the
//! hardware's cos γ is from the golden f64 front end's, and how far that moves the colour of
//! `bump` and of `normalizer-fit`'s specular path: for the formats built, for the 16-bit words
//! before them, and for other designs.
//! `-- --stages` rounds one word at a time; `-- --sweep` runs every design over 54 scenes. It
//! is a design tool, not a test: nothing here is asserted.
//!
//! The front end is modelled stage by stage, each word rounded to nearest (ties up) at its
//! fraction bits (`None` = kept exact), as in `rtl/src/units/normalizer.rs` and
//! `rtl/src/units/lighting_unit.rs`:
//!
//! ```text
//!                                              built            before
//! N   the vector interpolator's output         signed Q2.17     signed Q2.14
//! K   |N|² narrowed for the Horner multipliers unsigned Q1.15   unsigned Q1.15
//! t1  c2·K + c1                                signed Q2.17     signed Q2.14
//! f   t1·K + c0                                unsigned Q1.18   unsigned Q1.15
//! N'  N·f                                      signed Q2.17     signed Q2.14
//! H   the half vector register                 signed Q2.14     signed Q2.14
//! c   N'·H, rounded for the BRZSSK             unsigned Q1.15; the sin γ PROM takes 11 address
//!                                              bits and interpolates with the rest
//! ```
//! N went to Q2.17 a session after t1, f and N' (the "previous build" row keeps N at Q2.14).
//! The first design runs the built words through the bit-exact integer twin of the lighting
//! unit (`golden::units::lighting_unit::twin`) instead of the model, so the model can be compared
//! with it (the twin also floors the low parts of the 19-bit words' products, < 2⁻²⁸).
//! The twin gives cos γ only after its output rounding, so that row's |Δcos γ| includes it.
//!
//! The colour is compared per fragment (before the z-buffer) with the golden image whose sin γ
//! PROM interpolates with the same bits. The diffuse term is the golden one in both, so the
//! difference is the specular path's alone; the power unit's own error is not modelled.
//!
//! Near the highlight's centre cos(γ ± dγ) = c·cos dγ ∓ √(1 − c²)·sin dγ is steep in c (see
//! `tests/rtl_lit.rs`, `ill_conditioned`), and the power n multiplies any error in c. So the
//! bound needs both a finer c out of the lighting unit and a front end whose error is well
//! under one LSB of Q1.15.

use glam::DVec3;
use golden::shading::bump::{perturb, BumpMap, SinProm};
use shadecore::setup::{build, SceneArgs};

/// Fraction bits of each front-end word (`None`: exact).
#[derive(Clone, Copy)]
struct Formats {
    n: Option<u32>,
    k: Option<u32>,
    t1: Option<u32>,
    f: Option<u32>,
    n_prime: Option<u32>,
    h: Option<u32>,
    /// Fraction bits of c into the BRZSSK; the sin γ PROM interpolates with `c − 11` bits.
    c: u32,
}

/// The formats before the fix: every word 16 bits.
const BEFORE: Formats = Formats {
    n: Some(14),
    k: Some(15),
    t1: Some(14),
    f: Some(15),
    n_prime: Some(14),
    h: Some(14),
    c: 15,
};

/// The formats built (`rtl/src/units/normalizer.rs`, `rtl/src/units/vector_interpolator.rs`): N Q2.17,
/// t1 Q2.17, f Q1.18 and N' Q2.17, 19-bit words split 16 + 3 at their multipliers.
const BUILT: Formats = Formats {
    n: Some(17),
    ..PREVIOUS
};

/// The build before N was widened: t1 Q2.17, f Q1.18 and N' Q2.17, N still Q2.14.
const PREVIOUS: Formats = Formats {
    t1: Some(17),
    f: Some(18),
    n_prime: Some(17),
    ..BEFORE
};

/// The formats before the fix with every word `extra` bits wider, and c at `c` fraction bits.
fn wider(extra: u32, c: u32) -> Formats {
    let w = |b: Option<u32>| b.map(|b| b + extra);
    Formats {
        n: w(BEFORE.n),
        k: w(BEFORE.k),
        t1: w(BEFORE.t1),
        f: w(BEFORE.f),
        n_prime: w(BEFORE.n_prime),
        h: w(BEFORE.h),
        c,
    }
}

fn round(v: f64, frac: Option<u32>) -> f64 {
    match frac {
        Some(b) => {
            let s = (b as f64).exp2();
            (v * s + 0.5).floor() / s
        }
        None => v,
    }
}

fn round3(v: DVec3, frac: Option<u32>) -> DVec3 {
    DVec3::new(round(v.x, frac), round(v.y, frac), round(v.z, frac))
}

/// cos γ = N'·H through the modelled front end (unclamped, before the output rounding).
fn model(n: DVec3, h: DVec3, c: [f64; 3], f: &Formats) -> f64 {
    let n = round3(n, f.n);
    let k = round(n.length_squared(), f.k);
    let t1 = round(c[0] * k + c[1], f.t1);
    let scale = round(t1 * k + c[2], f.f);
    round3(n * scale, f.n_prime).dot(round3(h, f.h))
}

/// cos γ, after the output rounding, from the bit-exact integer twin of the lighting unit
/// (`golden::units::lighting_unit::twin`: the normalizer, the dot products, the Q1.15 narrowing).
fn twin(n: DVec3, h: DVec3, c: [f64; 3]) -> f64 {
    use golden::units::lighting_unit::twin::LightingTwin;
    let q = |v: DVec3, scale: f64| [v.x, v.y, v.z].map(|x| (x * scale + 0.5).floor() as i64);
    let h = q(h, 16384.0);
    let mut t = LightingTwin::new(c);
    t.clock(true, q(n, 131072.0), [0; 3], h);
    loop {
        let (valid, _, cos_gamma) = t.outputs();
        if valid {
            return cos_gamma as f64 / 32768.0;
        }
        t.clock(false, [0; 3], [0; 3], h);
    }
}

/// The largest difference between two colours' channels.
fn channel_diff(a: [u8; 3], b: [u8; 3]) -> u8 {
    (0..3).map(|i| a[i].abs_diff(b[i])).max().unwrap_or(0)
}

struct Outcome {
    dc_max: f64,
    lsb_max: u8,
    over_2: usize,
    /// The same for `normalizer-fit`'s specular path: c^n from the same c word.
    plain_lsb_max: u8,
}

fn run(args: &SceneArgs, formats: Option<&Formats>) -> Outcome {
    let s = build(args).expect("scene");
    let coeffs = golden::units::normalizer::FIT;
    let half = s.ctx.half();
    let map = BumpMap::default();
    let (phi, _) = golden::shading::bump::default_proms();
    let fm = formats.unwrap_or(&BUILT);
    let prom = SinProm {
        addr_bits: golden::shading::bump::SIN_ADDR_BITS,
        interp_bits: fm.c - golden::shading::bump::SIN_ADDR_BITS,
    };
    let top = (1i64 << (fm.c + 1)) - 1;
    let scale = (fm.c as f64).exp2();
    let mut o = Outcome {
        dc_max: 0.0,
        lsb_max: 0,
        over_2: 0,
        plain_lsb_max: 0,
    };
    for t in &s.tris {
        let w = golden::raster::walk(t);
        let Some(setup) = golden::units::normalizer::setup(t, &w) else {
            continue;
        };
        for p in golden::units::normalizer::interpolate(&setup, &w) {
            let (d, c_gold) = golden::units::normalizer::cosines(&p, &s.ctx, &coeffs.into());
            let c_hw = match formats {
                Some(f) => model(p.n, half, coeffs, f),
                None => twin(p.n, half, coeffs),
            };
            // Both clamped as the lighting unit's output is: a negative c only ever enters
            // the colour as 0.
            let clamp = |c: f64| c.clamp(0.0, golden::units::lighting_unit::COS_MAX);
            o.dc_max = o.dc_max.max((clamp(c_hw) - clamp(c_gold)).abs() * 32768.0);
            let c_word = ((c_hw * scale + 0.5).floor() as i64).clamp(0, top) as f64 / scale;
            let code = map.code(p.x, p.y);
            let diffuse = perturb(d, code, &map, &phi);
            let colour = |c: f64| {
                let spec = s.ctx.specular_power(perturb(c, code, &map, &prom));
                s.ctx.combine(diffuse, spec)
            };
            let lsb = channel_diff(colour(c_word), colour(c_gold));
            o.lsb_max = o.lsb_max.max(lsb);
            o.over_2 += (lsb > 2) as usize;
            let plain = |c: f64| s.ctx.combine(d, s.ctx.specular_power(c));
            o.plain_lsb_max = o
                .plain_lsb_max
                .max(channel_diff(plain(c_word), plain(c_gold)));
        }
    }
    o
}

fn main() {
    let scenes = [
        ("sphere 400²", SceneArgs::default()),
        (
            "torus 400²",
            SceneArgs {
                scene: "torus".into(),
                ..SceneArgs::default()
            },
        ),
        (
            "sphere 400², n = 1000",
            SceneArgs {
                shininess: 1000,
                ..SceneArgs::default()
            },
        ),
        (
            "torus rez 30 240²",
            SceneArgs {
                scene: "torus".into(),
                rez: 30,
                size: (240, 240),
                ..SceneArgs::default()
            },
        ),
    ];
    let designs: Vec<(&str, Option<Formats>)> = vec![
        ("built (N, t1, N' Q2.17; f Q1.18): integer twin", None),
        ("built: model", Some(BUILT)),
        (
            "previous build (N Q2.14; t1, N' Q2.17; f Q1.18): model",
            Some(PREVIOUS),
        ),
        ("before (every word 16 bits): model", Some(BEFORE)),
        (
            "N' not rounded (N·H before ·f)",
            Some(Formats {
                n_prime: None,
                ..BEFORE
            }),
        ),
        (
            "t1 Q2.17",
            Some(Formats {
                t1: Some(17),
                ..BEFORE
            }),
        ),
        (
            "N' not rounded, t1 Q2.17, c Q1.17",
            Some(Formats {
                n_prime: None,
                t1: Some(17),
                c: 17,
                ..BEFORE
            }),
        ),
        (
            "N' not rounded, t1 Q2.17, f Q1.18, c Q1.17",
            Some(Formats {
                n_prime: None,
                t1: Some(17),
                f: Some(18),
                c: 17,
                ..BEFORE
            }),
        ),
        (
            "N Q2.17, N' not rounded, t1 Q2.17, f Q1.18, c Q1.17",
            Some(Formats {
                n: Some(17),
                n_prime: None,
                t1: Some(17),
                f: Some(18),
                c: 17,
                ..BEFORE
            }),
        ),
        (
            "every word +2 bits (18-bit operands), c Q1.17",
            Some(wider(2, 17)),
        ),
        (
            "every word +2 bits but H, c Q1.17",
            Some(Formats {
                h: BEFORE.h,
                ..wider(2, 17)
            }),
        ),
        ("every word +3 bits, c Q1.15", Some(wider(3, 15))),
        ("every word +3 bits, c Q1.17", Some(wider(3, 17))),
        (
            "18-bit magnitudes: N, t1, N', H ±Q1.17; K, f Q1.17; c Q1.17",
            Some(Formats {
                n: Some(17),
                k: Some(17),
                t1: Some(17),
                f: Some(17),
                n_prime: Some(17),
                h: Some(17),
                c: 17,
            }),
        ),
        ("every word +4 bits, c Q1.18", Some(wider(4, 18))),
        ("every word +5 bits, c Q1.19", Some(wider(5, 19))),
    ];
    if std::env::args().any(|a| a == "--stages") {
        stages();
        return;
    }
    if std::env::args().any(|a| a == "--sweep") {
        sweep(&designs);
        return;
    }
    println!(
        "Against the golden images, per fragment: max |Δcos γ| in LSB of Q1.15 / `bump`'s max \
         colour difference in 8-bit LSB (fragments more than 2 LSB off) / the same for \
         `normalizer-fit`'s specular path\n"
    );
    print!("| front end |");
    for (name, _) in &scenes {
        print!(" {name} |");
    }
    println!();
    println!("|---|{}", "---:|".repeat(scenes.len()));
    for (label, formats) in &designs {
        print!("| {label} |");
        for (_, args) in &scenes {
            let o = run(args, formats.as_ref());
            print!(
                " {:.2} / {} ({}) / {} |",
                o.dc_max, o.lsb_max, o.over_2, o.plain_lsb_max
            );
        }
        println!();
    }
}

/// Per n: `bump`'s scenes over 2 LSB and its worst LSB; the same for `normalizer-fit`.
type Tally = (usize, u8, usize, u8);

/// `--sweep`: every design over 54 scenes (sphere and torus; 240², 400², 600²; light at 60°,
/// 90°, 120°; n = 50, 200 and 1000): per n, in how many scenes the colour is more than 2 LSB
/// off, and the worst; for `bump` and for `normalizer-fit`'s specular path (c^n).
fn sweep(designs: &[(&str, Option<Formats>)]) {
    let mut scenes = Vec::new();
    for scene in ["sphere", "torus"] {
        for size in [240, 400, 600] {
            for light_deg in [60.0, 90.0, 120.0] {
                for shininess in [50, 200, 1000] {
                    scenes.push(SceneArgs {
                        scene: scene.into(),
                        size: (size, size),
                        light_deg,
                        shininess,
                        ..SceneArgs::default()
                    });
                }
            }
        }
    }
    let per_n = scenes.len() / 3;
    println!(
        "| front end | `bump`: scenes over 2 LSB (of {per_n} per n), n = 50 / 200 / 1000 | `bump`: worst LSB | `normalizer-fit` specular path: scenes over 2 LSB | its worst LSB | worst max |Δcos γ| (LSB of Q1.15) |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    // The n = 50 scenes where `bump` is over 2 LSB, per design (listed after the table).
    let mut over_at_50 = Vec::new();
    for (label, formats) in designs {
        // Per n = 50, 200, 1000: (bump over, bump worst, plain over, plain worst).
        let mut t: [Tally; 3] = [(0, 0, 0, 0); 3];
        let mut dc = 0f64;
        for args in &scenes {
            let o = run(args, formats.as_ref());
            if args.shininess == 50 && o.lsb_max > 2 {
                over_at_50.push(format!(
                    "{label}: {} {}², light at {}°: {} LSB",
                    args.scene.display(),
                    args.size.0,
                    args.light_deg,
                    o.lsb_max
                ));
            }
            let slot = &mut t[match args.shininess {
                50 => 0,
                200 => 1,
                _ => 2,
            }];
            slot.0 += (o.lsb_max > 2) as usize;
            slot.1 = slot.1.max(o.lsb_max);
            slot.2 += (o.plain_lsb_max > 2) as usize;
            slot.3 = slot.3.max(o.plain_lsb_max);
            dc = dc.max(o.dc_max);
        }
        let col = |f: &dyn Fn(&Tally) -> String| t.iter().map(f).collect::<Vec<_>>().join(" / ");
        println!(
            "| {label} | {} | {} | {} | {} | {dc:.2} |",
            col(&|x| x.0.to_string()),
            col(&|x| x.1.to_string()),
            col(&|x| x.2.to_string()),
            col(&|x| x.3.to_string()),
        );
    }
    println!("\n`bump` over 2 LSB at n = 50:");
    for line in over_at_50 {
        println!("- {line}");
    }
}

/// `--stages`: on the default sphere, the worst |Δcos γ| when only one word is rounded (at
/// its format before the fix) and every other word is exact; then all of them, before and
/// built.
fn stages() {
    let exact = Formats {
        n: None,
        k: None,
        t1: None,
        f: None,
        n_prime: None,
        h: None,
        c: BEFORE.c,
    };
    let rows = [
        (
            "N, the vector interpolator's output (signed Q2.14)",
            Formats {
                n: BEFORE.n,
                ..exact
            },
        ),
        (
            "N' = N·f (signed Q2.14)",
            Formats {
                n_prime: BEFORE.n_prime,
                ..exact
            },
        ),
        (
            "t1 = c2·K + c1 (signed Q2.14)",
            Formats {
                t1: BEFORE.t1,
                ..exact
            },
        ),
        (
            "f = t1·K + c0 (unsigned Q1.15)",
            Formats {
                f: BEFORE.f,
                ..exact
            },
        ),
        (
            "K for the Horner multipliers (unsigned Q1.15)",
            Formats {
                k: BEFORE.k,
                ..exact
            },
        ),
        (
            "H, the half vector (signed Q2.14)",
            Formats {
                h: BEFORE.h,
                ..exact
            },
        ),
        ("all but H", Formats { h: None, ..BEFORE }),
        ("all: before", BEFORE),
        (
            "all: previous build (N Q2.14; t1, N' Q2.17; f Q1.18)",
            PREVIOUS,
        ),
        ("all: built (N, t1, N' Q2.17; f Q1.18)", BUILT),
    ];
    println!("| word rounded (every other word exact) | worst |Δcos γ|, LSB of Q1.15 |");
    println!("|---|---:|");
    for (label, f) in rows {
        let o = run(&SceneArgs::default(), Some(&f));
        println!("| {label} | {:.2} |", o.dc_max);
    }
}
