//! Shading through the four-triangle block (issue 12): Gouraud with `--address four-triangle`
//! and the `subdivision` method, each against the golden image of the same method (same
//! coverage, at most 1 LSB per channel), and `subdivision` against the reference beside
//! Gouraud's NMSE, on the default sphere, a torus and an irregular OBJ mesh; the CLI's
//! errors for an address block a method cannot take.

use golden::methods::Method;
use golden::render::render;
use indicatif::ProgressBar;
use shadecore::rtl_engine::{max_channel_diff, render_rtl_with, Address, RtlBuild};
use shadecore::setup::{build, SceneArgs};

fn check_scene(label: &str, args: &SceneArgs) {
    let s = build(args).unwrap();
    let reference = render(&s.tris, Method::Reference, &s.ctx, s.width, s.height);
    let mut nmse = Vec::new();
    for (m, address) in [
        (Method::Gouraud, Address::FourTriangle),
        (Method::Subdivision, Address::Default),
    ] {
        let build = RtlBuild {
            address,
            ..RtlBuild::default()
        };
        let rtl = render_rtl_with(&s, m, build, &ProgressBar::hidden())
            .unwrap_or_else(|e| panic!("{label} {m}: {e:#}"));
        let gold = render(&s.tris, m, &s.ctx, s.width, s.height);
        assert_eq!(
            rtl.frame.fragments, gold.fragments,
            "{label} {m}: coverage differs"
        );
        assert!(
            rtl.frame.fragments.iter().all(|&n| n <= 1) || label.contains("torus"),
            "{label} {m}: a pixel written twice on a convex mesh"
        );
        let (max, n) = max_channel_diff(&rtl.frame, &gold);
        let e = golden::nmse::nmse(&reference.rgb, &rtl.frame.rgb);
        let eg = golden::nmse::nmse(&reference.rgb, &gold.rgb);
        println!(
            "{label} {m} (four-triangle block): NMSE {e:.3e} (golden {eg:.3e}); vs golden max {max} LSB, {n} pixels differ; {} pixels in {} clocks ({:.3} pixels/clock)",
            rtl.stats.pixels,
            rtl.stats.clocks,
            rtl.stats.pixels_per_clock()
        );
        assert!(max <= 1, "{label} {m}: {max} LSB from the golden image");
        nmse.push(e);
    }
    assert!(
        nmse[1] < 0.5 * nmse[0],
        "{label}: subdivision NMSE {:.3e} is not clearly below Gouraud's {:.3e}",
        nmse[1],
        nmse[0]
    );
}

#[test]
fn default_scene_through_the_four_triangle_block() {
    check_scene("sphere rez 50", &SceneArgs::default());
}

#[test]
fn torus_through_the_four_triangle_block() {
    check_scene(
        "torus rez 20",
        &SceneArgs {
            scene: "torus".into(),
            rez: 20,
            ..SceneArgs::default()
        },
    );
}

fn shadecore(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_shadecore"))
        .args(args)
        .output()
        .expect("run shadecore")
}

#[test]
fn address_choices_a_method_cannot_take_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    for (args, what) in [
        (
            vec!["--method", "angular", "--address", "four-triangle"],
            "--address has no effect here: it concerns gouraud or subdivision",
        ),
        (
            vec!["--method", "subdivision", "--address", "single"],
            "four-triangle block",
        ),
    ] {
        let mut a = vec![
            "render", "--engine", "rtl", "--size", "40x40", "--rez", "6", "--out", out,
        ];
        a.extend(args);
        let o = shadecore(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{a:?} succeeded");
        assert!(err.contains(what), "{a:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{a:?}: {err}");
    }
}
