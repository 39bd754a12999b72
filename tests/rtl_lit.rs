//! The lit pixel pipeline renders images (issue "The lit pixel pipeline"): every lit method
//! through the simulated RTL (`shadecore::rtl_engine::render_rtl`) against the golden image of
//! the same method (max LSB per channel, pixels differing, identical coverage) and against the
//! reference (NMSE), on the default sphere, the torus and an OBJ mesh generated here.
//!
//! Bounds: every method within 2 LSB per channel of its golden image at every pixel, `bump`
//! included (its pixels where the method is ill-conditioned, [`ill_conditioned`], are counted
//! and printed apart: they were the last to meet the bound); on the default scene
//! `normalizer-fit` and `brdf-k16` reach NMSE ≤ 10⁻⁴ against the reference; no pixel may see a
//! different surface than the f64 depth planes pick, except where two surfaces are closer
//! than the depth words resolve (counted and printed; these scenes have none).

use golden::methods::Method;
use golden::render::render;
use indicatif::ProgressBar;
use pipeline::lit::LIT_METHODS;
use shadecore::rtl_engine::{max_channel_diff, render_rtl};
use shadecore::setup::{build, SceneArgs};

/// The pixels where `bump` is ill-conditioned: cos(γ ± dγ) = c·cos dγ ∓ √(1 − c²)·sin dγ has
/// the slope cos dγ ± sin dγ·c/√(1 − c²) in c, unbounded as c → 1 (the highlight's centre),
/// so the lighting unit's own error on c (`golden::units::lighting_unit::error_bound` of the
/// normalizer's format-derived budget: ≤ 6.1·10⁻⁵ with the fitted coefficients) moves S by up to
/// n·S^((n−1)/n)·sin|dγ|·c/√(1 − c²)·Δc. Where that exceeds one 8-bit LSB of the specular
/// colour, no implementation whose c is off by Δc can stay within 2 LSB of the f64 golden.
/// Computed from the golden front end's c at each pixel of every triangle.
fn ill_conditioned(s: &shadecore::setup::Setup) -> Vec<bool> {
    use golden::shading::bump::BumpMap;
    // The lighting unit's bound on cos γ, from the normalizer's format-derived budget on its
    // domain (fitted coefficients) and the half vector it is dotted with.
    let coeffs =
        rtl::units::normalizer::NormalizerCoeffs::new(golden::units::normalizer::FIT).unwrap();
    let budget = testbenches::units::normalizer::domain_budget(&coeffs);
    let dc = golden::units::lighting_unit::error_bound(budget.component_max, s.ctx.half());
    let n = s.ctx.n() as f64;
    let spec = s.ctx.material.ks * s.ctx.material.specular.iter().cloned().fold(0.0, f64::max);
    let map = BumpMap::default();
    let mut mask = vec![false; (s.width * s.height) as usize];
    for t in &s.tris {
        if t.depth_plane().is_none() {
            continue;
        }
        let w = golden::raster::walk(t);
        let mut hits = Vec::new();
        golden::units::normalizer::shade_front_end(
            t,
            &w,
            &s.ctx,
            golden::units::normalizer::FIT,
            &mut |_, _, _| {},
            |x, y, _, c| {
                let c = c.clamp(0.0, 1.0);
                let sd = map.d_gamma(x, y).abs().sin();
                let (_, cp) = golden::units::brzssk::brzssk(0.0, c, x, y);
                let slope = sd * c / (1.0 - c * c).max(1e-30).sqrt();
                let ds = n * cp.max(0.0).powf((n - 1.0) / n) * slope * dc;
                if spec * ds > 1.0 {
                    hits.push((x, y));
                }
                [0; 3]
            },
        );
        for (x, y) in hits {
            if (0..s.width as i32).contains(&x) && (0..s.height as i32).contains(&y) {
                mask[(y as u32 * s.width + x as u32) as usize] = true;
            }
        }
    }
    mask
}

/// (Largest channel difference, pixels more than 2 LSB off) outside `mask`, and the same
/// inside it.
fn split_diff(
    a: &golden::render::Frame,
    b: &golden::render::Frame,
    mask: &[bool],
) -> ((u8, usize), (u8, usize)) {
    let (mut out, mut inside) = ((0u8, 0usize), (0u8, 0usize));
    for ((p, q), &m) in a.rgb.iter().zip(&b.rgb).zip(mask) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        let slot = if m { &mut inside } else { &mut out };
        slot.0 = slot.0.max(d);
        slot.1 += (d > 2) as usize;
    }
    (out, inside)
}

/// Render every lit method of `args` through the RTL and check it against golden.
fn check_scene(label: &str, args: &SceneArgs, nmse_bound: &[(Method, f64)]) {
    let s = build(args).unwrap();
    let reference = render(&s.tris, Method::Reference, &s.ctx, s.width, s.height);
    for m in LIT_METHODS {
        let t0 = std::time::Instant::now();
        let rtl = render_rtl(
            &s.tris,
            m,
            &s.ctx,
            s.width,
            s.height,
            &ProgressBar::hidden(),
        )
        .unwrap_or_else(|e| panic!("{label} {m}: {e:#}"));
        let gold = golden::render::render(&s.tris, m, &s.ctx, s.width, s.height);
        assert_eq!(
            rtl.frame.fragments, gold.fragments,
            "{label} {m}: coverage differs"
        );
        let (max, n) = max_channel_diff(&rtl.frame, &gold);
        let nmse = golden::nmse::nmse(&reference.rgb, &rtl.frame.rgb);
        println!(
            "{label} {m}: {} fragments in {} clocks ({:.3}/clock, {:.1} s); vs golden max {max} LSB, \
             {n} pixels differ; NMSE vs reference {nmse:.3e}; {} pixels with other visibility",
            rtl.stats.pixels,
            rtl.stats.clocks,
            rtl.stats.pixels_per_clock(),
            t0.elapsed().as_secs_f64(),
            rtl.visibility_mismatches
        );
        if m == Method::Bump {
            let mask = ill_conditioned(&s);
            let ((out_max, out_n), (in_max, in_n)) = split_diff(&rtl.frame, &gold, &mask);
            println!(
                "{label} bump: {} ill-conditioned pixels (highlight centre): max {in_max} LSB, \
                 {in_n} by more than 2; elsewhere max {out_max} LSB, {out_n} by more than 2",
                mask.iter().filter(|&&b| b).count()
            );
            assert!(
                out_max <= 2,
                "{label} bump: {out_max} LSB outside the ill-conditioned zone"
            );
        }
        assert!(
            max <= 2,
            "{label} {m}: RTL differs from golden by {max} LSB"
        );
        assert_eq!(
            rtl.visibility_mismatches, 0,
            "{label} {m}: visibility differs"
        );
        if let Some((_, b)) = nmse_bound.iter().find(|(mm, _)| *mm == m) {
            assert!(nmse <= *b, "{label} {m}: NMSE {nmse:.3e} > {b}");
        }
    }
}

#[test]
fn default_scene_every_lit_method_through_the_rtl() {
    check_scene(
        "sphere rez 50 400x400",
        &SceneArgs::default(),
        &[(Method::NormalizerFit, 1e-4), (Method::BrdfK16, 1e-4)],
    );
}

#[test]
fn torus_every_lit_method_through_the_rtl() {
    let args = SceneArgs {
        scene: "torus".into(),
        rez: 30,
        size: (240, 240),
        ..SceneArgs::default()
    };
    check_scene("torus rez 30 240x240", &args, &[]);
}

/// A lumpy closed mesh without normals (the loader computes smooth ones): latitude-longitude
/// grid on r(θ, φ) = 1 + 0.15·sin 3θ·cos 2φ.
fn lumpy_obj() -> String {
    use std::f64::consts::PI;
    use std::fmt::Write;
    let (nu, nv) = (32, 16);
    let mut s = String::from("# generated by tests/rtl_lit.rs\n");
    for j in 0..=nv {
        let th = PI * j as f64 / nv as f64;
        for i in 0..nu {
            let ph = 2.0 * PI * i as f64 / nu as f64;
            let r = 1.0 + 0.15 * (3.0 * th).sin() * (2.0 * ph).cos();
            let (x, y, z) = (
                r * th.sin() * ph.cos(),
                r * th.cos(),
                r * th.sin() * ph.sin(),
            );
            writeln!(s, "v {x:.6} {y:.6} {z:.6}").unwrap();
        }
    }
    let idx = |i: usize, j: usize| j * nu + (i % nu) + 1;
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            writeln!(s, "f {a} {d} {c}\nf {a} {c} {b}").unwrap();
        }
    }
    s
}

#[test]
fn generated_obj_every_lit_method_through_the_rtl() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lumpy.obj");
    std::fs::write(&path, lumpy_obj()).unwrap();
    let args = SceneArgs {
        scene: path.to_str().unwrap().into(),
        size: (200, 200),
        ..SceneArgs::default()
    };
    // `bump` was 3 LSB off at one pixel of the highlight's centre until N left the vector
    // interpolator at Q2.17 (2 LSB with the 16-bit front end, 3 after t1, f and N' got three
    // more bits); see the README.
    check_scene("lumpy.obj 200x200", &args, &[]);
}

#[test]
fn bad_rtl_input_is_a_one_line_error() {
    let s = build(&SceneArgs {
        size: (40, 40),
        rez: 6,
        ..SceneArgs::default()
    })
    .unwrap();
    let bar = ProgressBar::hidden();
    // A method the hardware does not have names the ones it has.
    let e = render_rtl(&s.tris, Method::Flat, &s.ctx, 40, 40, &bar).unwrap_err();
    let msg = format!("{e:#}");
    assert!(
        msg.contains("no hardware for method flat") && msg.contains("brdf-k16"),
        "{msg}"
    );
    assert!(!msg.contains('\n'));
    // Phong lighting is not built.
    let mut ctx = s.ctx;
    ctx.lighting = golden::shade::LightingModel::Phong;
    let e = render_rtl(&s.tris, Method::NormalizerFit, &ctx, 40, 40, &bar).unwrap_err();
    assert!(format!("{e:#}").contains("phong"), "{e:#}");
    // n outside 1..=1000.
    let mut ctx = s.ctx;
    ctx.material.shininess = 1001;
    let e = render_rtl(&s.tris, Method::Normalizer, &ctx, 40, 40, &bar).unwrap_err();
    assert!(format!("{e:#}").contains("outside 1..=1000"), "{e:#}");
    // A colour weight the Q8.8 register cannot hold.
    let mut ctx = s.ctx;
    ctx.material.ks = 1.5;
    let e = render_rtl(&s.tris, Method::BrdfK16, &ctx, 40, 40, &bar).unwrap_err();
    assert!(format!("{e:#}").contains("spc_r"), "{e:#}");
}

/// Lambert lighting through the RTL: the set-up loads zero specular weights, so the image has
/// no highlight and equals the golden Lambert image of the same method within 2 LSB.
#[test]
fn lambert_lighting_through_the_rtl() {
    let args = SceneArgs {
        size: (120, 120),
        rez: 12,
        lighting: shadecore::setup::Lighting::Lambert,
        ..SceneArgs::default()
    };
    let s = build(&args).unwrap();
    for m in [Method::NormalizerFit, Method::Bump] {
        let rtl = render_rtl(
            &s.tris,
            m,
            &s.ctx,
            s.width,
            s.height,
            &ProgressBar::hidden(),
        )
        .unwrap();
        let gold = golden::render::render(&s.tris, m, &s.ctx, s.width, s.height);
        let (max, n) = max_channel_diff(&rtl.frame, &gold);
        println!("lambert {m}: max {max} LSB, {n} pixels differ");
        assert!(max <= 2, "lambert {m}: {max} LSB");
        // No specular term: no channel reaches the diffuse colour's ambient + full diffuse
        // plus anything (the brightest pixel is at most the diffuse colour's own level + 1).
        let top = rtl.frame.rgb.iter().map(|p| p[2]).max().unwrap();
        let limit = (s.ctx.material.diffuse[2] * (1.0 + s.ctx.material.ka)).round() as u8 + 1;
        assert!(top <= limit, "lambert {m}: blue reaches {top} > {limit}");
    }
}
