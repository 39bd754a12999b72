//! Shading methods: names, sanity on simple triangles, agreement with the reference where the
//! approximations must be exact, the K recurrence, and image quality on the thesis sphere.

use glam::{DQuat, DVec3};
use golden::methods::{shade_triangle, Emit, Method};
use golden::shade::{LightingModel, Material, ShadeContext};
use golden::testing::runner;
use golden::types::{ScreenTriangle, ScreenVertex, Walk};
use golden::{raster, scene};
use proptest::prelude::*;

/// Render `tris` with `method` into a `w`×`h` frame with a depth buffer (nearer z wins).
fn render(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    w: u32,
    h: u32,
) -> Vec<[u8; 3]> {
    render_with(tris, w, h, |tri, walk, emit| {
        shade_triangle(method, tri, walk, ctx, emit)
    })
}

/// Render `tris` into a `w`×`h` frame with a depth buffer (nearer z wins), each triangle shaded
/// by `shade_one(triangle, walk, emit)`.
fn render_with(
    tris: &[ScreenTriangle],
    w: u32,
    h: u32,
    shade_one: impl Fn(&ScreenTriangle, &Walk, Emit),
) -> Vec<[u8; 3]> {
    let mut rgb = vec![[0u8; 3]; (w * h) as usize];
    let mut depth = vec![f64::INFINITY; (w * h) as usize];
    for tri in tris {
        let Some(dp) = tri.depth_plane() else {
            continue;
        };
        let walk = raster::walk(tri);
        shade_one(tri, &walk, &mut |x, y, c| {
            if x < 0 || y < 0 || x >= w as i32 || y >= h as i32 {
                return;
            }
            let i = (y as u32 * w + x as u32) as usize;
            let z = dp.at_pixel(x, y);
            if z < depth[i] {
                depth[i] = z;
                rgb[i] = c;
            }
        });
    }
    rgb
}

/// The thesis sphere, projected by the golden scene code (viewer-facing half only).
fn sphere_scene(rez: u32, size: u32) -> Vec<ScreenTriangle> {
    let mesh = scene::uv_sphere(rez).unwrap();
    let cam = scene::Camera::fit(&mesh, size, size, DQuat::IDENTITY);
    let tris = scene::project(&mesh, &cam, size, size).unwrap();
    assert!(
        tris.iter().all(|t| t.v.iter().any(|v| v.normal.z > 0.0)),
        "back faces kept"
    );
    tris
}

fn ctx_for(n: u32, light_deg: f64, lighting: LightingModel) -> ShadeContext {
    let material = Material {
        shininess: n,
        ..Material::default()
    };
    ShadeContext::new(
        material,
        lighting,
        scene::light_direction(light_deg).unwrap(),
        DVec3::Z,
    )
    .unwrap()
}

/// NMSE of every method against the reference on a sphere.
fn sphere_nmse(rez: u32, n: u32, light_deg: f64, lighting: LightingModel) -> Vec<(Method, f64)> {
    let size = 400;
    let tris = sphere_scene(rez, size);
    let ctx = ctx_for(n, light_deg, lighting);
    let reference = render(&tris, Method::Reference, &ctx, size, size);
    Method::ALL_NON_REFERENCE
        .iter()
        .map(|&m| {
            (
                m,
                golden::nmse::nmse(&reference, &render(&tris, m, &ctx, size, size)),
            )
        })
        .collect()
}

/// The NMSE of `m` in a table of [`sphere_nmse`].
fn nmse_of(table: &[(Method, f64)], m: Method) -> f64 {
    table.iter().find(|(x, _)| *x == m).unwrap().1
}

/// Issue 2's bounds on the thesis sphere: normalizer-fit ≤ 0.0001; fast-fit, angular, quadric,
/// cubic and brdf-k16 ≤ 0.00025 against the reference.
fn assert_issue_2_bounds(table: &[(Method, f64)], lighting: &str) {
    let fit = nmse_of(table, Method::NormalizerFit);
    assert!(fit <= 0.0001, "{lighting} normalizer-fit {fit}");
    for m in [
        Method::FastFit,
        Method::Angular,
        Method::Quadric,
        Method::Cubic,
        Method::BrdfK16,
    ] {
        let v = nmse_of(table, m);
        assert!(v <= 0.00025, "{lighting} {m}: {v}");
    }
}

// ---------------------------------------------------------------- helpers

fn vertex(x: i32, y: i32, n: DVec3) -> ScreenVertex {
    ScreenVertex {
        x,
        y,
        z: 0.0,
        normal: n.normalize(),
        uv: glam::DVec2::ZERO,
        w: 1.0,
    }
}

/// A smooth triangle of a convex surface seen from the front: normals about 10° apart.
fn simple_triangle() -> ScreenTriangle {
    ScreenTriangle {
        v: [
            vertex(10, 5, DVec3::new(-0.10, 0.45, 0.89)),
            vertex(40, 20, DVec3::new(0.05, 0.30, 0.95)),
            vertex(15, 35, DVec3::new(-0.12, 0.22, 0.97)),
        ],
        frac: 0,
    }
}

/// Colours of `method` on `tri`, keyed by pixel, in emission order.
fn shade(method: Method, tri: &ScreenTriangle, ctx: &ShadeContext) -> Vec<((i32, i32), [u8; 3])> {
    let walk = raster::walk(tri);
    let mut out = Vec::new();
    shade_triangle(method, tri, &walk, ctx, &mut |x, y, c| {
        out.push(((x, y), c))
    });
    out
}

fn max_channel_diff(a: &[((i32, i32), [u8; 3])], b: &[((i32, i32), [u8; 3])]) -> u8 {
    a.iter()
        .zip(b)
        .flat_map(|((_, p), (_, q))| (0..3).map(move |c| p[c].abs_diff(q[c])))
        .max()
        .unwrap_or(0)
}

/// Random unit vector within `max_deg` of `axis`.
fn near(axis: DVec3) -> impl Strategy<Value = DVec3> {
    (-0.35f64..0.35, -0.35f64..0.35, -0.35f64..0.35)
        .prop_map(move |(a, b, c)| (axis + DVec3::new(a, b, c)).normalize())
}

/// Random front-facing triangles in a 160×160 box (including thin and one-pixel ones), with
/// smooth normals at most about 45° apart.
fn triangles() -> impl Strategy<Value = ScreenTriangle> {
    let axis = DVec3::new(0.2, 0.3, 0.93).normalize();
    (
        (0..160i32, 0..160i32),
        (0..160i32, 0..160i32),
        (0..160i32, 0..160i32),
        near(axis),
        near(axis),
        near(axis),
    )
        .prop_map(|(a, b, c, na, nb, nc)| ScreenTriangle {
            v: [
                vertex(a.0, a.1, na),
                vertex(b.0, b.1, nb),
                vertex(c.0, c.1, nc),
            ],
            frac: 0,
        })
}

/// Runs `check(triangle, context, set-up)` on 300 random triangles, seeded by `name`, with the
/// default shading context; triangles whose `setup` is `None` (degenerate) are skipped.
fn on_random_setups<S>(
    name: &str,
    setup: impl Fn(&ScreenTriangle, &ShadeContext) -> Option<S>,
    check: impl Fn(&ScreenTriangle, &ShadeContext, S) -> Result<(), TestCaseError>,
) {
    let ctx = ShadeContext::default();
    runner(name, 300)
        .run(&triangles(), |tri| match setup(&tri, &ctx) {
            Some(s) => check(&tri, &ctx, s),
            None => Ok(()),
        })
        .unwrap();
}

/// Whether `value(channel, x, y)` is within 1e-6 of the exact intensity of the normal at each
/// node ((x, y), normal).
fn passes_through(
    ctx: &ShadeContext,
    nodes: impl IntoIterator<Item = ((f64, f64), DVec3)>,
    value: impl Fn(usize, f64, f64) -> f64,
) -> Result<(), TestCaseError> {
    for ((x, y), n) in nodes {
        for (c, want) in ctx.exact_intensity(n).into_iter().enumerate() {
            let v = value(c, x, y);
            prop_assert!(
                (v - want).abs() < 1e-6,
                "node ({}, {}) channel {}: {} vs {}",
                x,
                y,
                c,
                v,
                want
            );
        }
    }
    Ok(())
}

fn lightings() -> [LightingModel; 3] {
    [
        LightingModel::Blinn,
        LightingModel::Phong,
        LightingModel::Lambert,
    ]
}

// ---------------------------------------------------------------- names

#[test]
fn method_names_round_trip() {
    let expected = [
        "reference",
        "flat",
        "gouraud",
        "subdivision",
        "normalizer",
        "normalizer-fit",
        "normalizer-pw",
        "fast",
        "fast-fit",
        "angular",
        "quadric",
        "cubic",
        "brdf-k4",
        "brdf-k8",
        "brdf-k16",
        "bump",
        "texture-reference",
        "texture",
        "texture-quadratic",
        "texture-bezier",
        "texture-affine",
    ];
    let names: Vec<&str> = Method::all().map(Method::name).collect();
    assert_eq!(names, expected);
    for m in Method::all() {
        assert_eq!(m.name().parse::<Method>(), Ok(m));
        assert_eq!(m.to_string(), m.name());
    }
    assert_eq!(Method::ALL_NON_REFERENCE.len(), 15);
    assert!(!Method::ALL_NON_REFERENCE.contains(&Method::Reference));
    for m in Method::all() {
        let textured = m.name().starts_with("texture");
        assert_eq!(m.is_textured(), textured, "{m}");
        let want = if textured {
            "texture-reference"
        } else {
            "reference"
        };
        assert_eq!(m.reference_of().name(), want, "{m}");
    }
}

#[test]
fn bad_method_names_error_with_the_valid_list() {
    for bad in [
        "",
        "Phong",
        "normaliser",
        "brdf-k32",
        "fast fit",
        "reference ",
    ] {
        let err = bad.parse::<Method>().unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains(&format!("{bad:?}")), "{msg}");
        assert!(!msg.contains('\n'), "one line: {msg}");
        for m in Method::all() {
            assert!(msg.contains(m.name()), "{msg} lacks {}", m.name());
        }
    }
}

// ---------------------------------------------------------------- context and combine

#[test]
fn bad_shading_input_is_a_one_line_error() {
    let m = Material::default();
    let cases = [
        ShadeContext::new(
            m,
            LightingModel::Blinn,
            DVec3::new(f64::NAN, 0.0, 1.0),
            DVec3::Z,
        ),
        ShadeContext::new(m, LightingModel::Blinn, DVec3::ZERO, DVec3::Z),
        ShadeContext::new(
            m,
            LightingModel::Blinn,
            DVec3::Z,
            DVec3::new(0.0, f64::INFINITY, 0.0),
        ),
        ShadeContext::new(
            Material { shininess: 0, ..m },
            LightingModel::Blinn,
            DVec3::Z,
            DVec3::Z,
        ),
        ShadeContext::new(
            Material {
                shininess: 1001,
                ..m
            },
            LightingModel::Blinn,
            DVec3::Z,
            DVec3::Z,
        ),
        ShadeContext::new(
            Material { kd: -1.0, ..m },
            LightingModel::Blinn,
            DVec3::Z,
            DVec3::Z,
        ),
        ShadeContext::new(
            Material {
                diffuse: [0.0, 300.0, 0.0],
                ..m
            },
            LightingModel::Blinn,
            DVec3::Z,
            DVec3::Z,
        ),
    ];
    for c in cases {
        let msg = c.unwrap_err().to_string();
        assert!(!msg.is_empty() && !msg.contains('\n'), "{msg}");
    }
    assert!("torrance".parse::<LightingModel>().is_err());
    for n in [1, 50, 1000] {
        let ok = ShadeContext::new(
            Material { shininess: n, ..m },
            LightingModel::Phong,
            DVec3::X * 3.0,
            DVec3::Z,
        );
        assert!((ok.unwrap().light.length() - 1.0).abs() < 1e-15);
    }
}

#[test]
fn combine_follows_the_spec_formula_with_the_thesis_defaults() {
    let ctx = ShadeContext::default();
    // Ambient only: k_a·D = D·50/255 → 12.55, 15.10, 17.65.
    assert_eq!(ctx.combine(-0.3, 0.0), [13, 15, 18]);
    // Facing the light, no highlight: D·(1 + 50/255) → 76.55, 92.10, 107.65.
    assert_eq!(ctx.combine(1.0, 0.0), [77, 92, 108]);
    // Half a highlight adds 127.5 of white: 204.05, 219.6, 235.15.
    assert_eq!(ctx.combine(1.0, 0.5), [204, 220, 235]);
    // Saturates rather than wraps.
    assert_eq!(ctx.combine(1.0, 1.0), [255, 255, 255]);
    // Lambert ignores the specular term.
    let lambert = ShadeContext {
        lighting: LightingModel::Lambert,
        ..ctx
    };
    assert_eq!(lambert.combine(1.0, 1.0), [77, 92, 108]);
}

#[test]
fn phong_lighting_is_r_dot_v() {
    // R = 2(N·L)N − L computed explicitly, against the method-side identity 2(N·L)(N·V) − L·V.
    runner("phong_lighting_is_r_dot_v", 500)
        .run(
            &(near(DVec3::Z), near(DVec3::new(0.5, 0.5, 0.7).normalize())),
            |(n, l)| {
                let ctx = ShadeContext::new(Material::default(), LightingModel::Phong, l, DVec3::Z)
                    .unwrap();
                let r = 2.0 * n.dot(l) * n - l;
                let (d, s) = ctx.exact_terms(n);
                prop_assert!((d - n.dot(l)).abs() < 1e-12);
                prop_assert!((s - r.dot(DVec3::Z).max(0.0).powi(50)).abs() < 1e-12);
                Ok(())
            },
        )
        .unwrap();
}

// ---------------------------------------------------------------- every method, every pixel

#[test]
fn every_method_emits_each_walk_pixel_once_in_walk_order_but_subdivision_lane_by_lane() {
    runner("every_method_emits_each_walk_pixel_once", 150)
        .run(&triangles(), |tri| {
            let walk = raster::walk(&tri);
            let expected: Vec<(i32, i32)> = walk.pixels().iter().map(|p| (p.x, p.y)).collect();
            for lighting in lightings() {
                let ctx = ShadeContext {
                    lighting,
                    ..ShadeContext::default()
                };
                for m in Method::all() {
                    let mut got: Vec<(i32, i32)> =
                        shade(m, &tri, &ctx).into_iter().map(|(p, _)| p).collect();
                    if m == Method::Subdivision {
                        // Lane by lane (the four-triangle block's order): the same pixels,
                        // each once, in another order.
                        let mut want = expected.clone();
                        want.sort_unstable();
                        got.sort_unstable();
                        prop_assert_eq!(&got, &want, "{} {:?}", m, lighting);
                        continue;
                    }
                    prop_assert_eq!(&got, &expected, "{} {:?}", m, lighting);
                }
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn methods_are_sane_on_a_simple_triangle() {
    let tri = simple_triangle();
    for lighting in lightings() {
        let ctx = ShadeContext {
            lighting,
            ..ShadeContext::default()
        };
        let reference = shade(Method::Reference, &tri, &ctx);
        assert!(reference.len() > 300, "{} pixels", reference.len());
        let floor = ctx.combine(0.0, 0.0);
        // The textured methods' diffuse colour is the texel's, not the material's: their floor
        // is the texel's ambient (`textured_methods_light_the_texel`).
        for m in Method::all().filter(|m| !m.is_textured()) {
            let got = shade(m, &tri, &ctx);
            // Never below the ambient floor.
            for (p, c) in &got {
                assert!(
                    (0..3).all(|i| c[i] >= floor[i]),
                    "{m} {lighting:?} {p:?} {c:?} below {floor:?}"
                );
            }
            // The accurate methods stay within a couple of LSB of the reference on a small
            // smooth triangle; the rest are only required to be in the same ballpark.
            let tol = match m {
                Method::Reference
                | Method::NormalizerFit
                | Method::NormalizerPw
                | Method::FastFit
                | Method::Angular => 1,
                Method::Quadric | Method::Cubic | Method::BrdfK16 => 2,
                _ => 80,
            };
            let d = max_channel_diff(&got, &reference);
            assert!(d <= tol, "{m} {lighting:?}: max diff {d} > {tol}");
        }
    }
}

/// With all three vertex normals equal, every approximation is evaluated at its exact point
/// (K = 1, M = 0, φ = 0, constant samples), so the methods must reproduce the reference; the
/// published coefficients must be off by exactly their bias f = 1.003.
#[test]
fn flat_normal_triangle_agrees_with_the_reference() {
    let n = DVec3::new(0.3, 0.2, 0.93).normalize();
    let tri = ScreenTriangle {
        v: [vertex(3, 2, n), vertex(11, 6, n), vertex(5, 12, n)],
        frac: 0,
    };
    for lighting in lightings() {
        let ctx = ShadeContext {
            lighting,
            ..ShadeContext::default()
        };
        let reference = shade(Method::Reference, &tri, &ctx);
        assert!(!reference.is_empty());
        for m in [
            Method::Flat,
            Method::Gouraud,
            Method::NormalizerFit,
            Method::NormalizerPw,
            Method::FastFit,
            Method::Angular,
            Method::Quadric,
            Method::Cubic,
        ] {
            assert_eq!(shade(m, &tri, &ctx), reference, "{m} {lighting:?}");
        }
        // Published forms: N scaled by 1.003 everywhere.
        let nn = n * 1.003;
        let cos_s = ctx.specular_vector().map_or(0.0, |x| nn.dot(x));
        let (d, s) = ctx.cosines(nn.dot(ctx.light), cos_s);
        let biased = ctx.combine(d, ctx.specular_power(s));
        for m in [Method::Normalizer, Method::Fast] {
            for (p, c) in shade(m, &tri, &ctx) {
                assert_eq!(c, biased, "{m} {lighting:?} at {p:?}");
            }
        }
    }
}

// ---------------------------------------------------------------- normalizer (§1)

#[test]
fn constant_increments_reproduce_the_normal_plane_and_k_equals_length_squared() {
    use golden::units::normalizer;
    on_random_setups(
        "k_recurrence_equals_length_squared",
        |tri, _| {
            let walk = raster::walk(tri);
            normalizer::setup(tri, &walk).map(|setup| (walk, setup))
        },
        |tri, _, (walk, setup)| {
            let plane = tri.normal_plane().unwrap();
            let pixels = normalizer::interpolate(&setup, &walk);
            prop_assert_eq!(pixels.len(), walk.pixel_count());
            for p in pixels {
                let exact = plane.at_pixel(p.x, p.y);
                prop_assert!(
                    (p.n - exact).length() < 1e-9,
                    "N at {:?}: {} vs {}",
                    (p.x, p.y),
                    p.n,
                    exact
                );
                prop_assert!(
                    (p.k - p.n.length_squared()).abs() < 1e-9,
                    "K at {:?}",
                    (p.x, p.y)
                );
                // The normalizer's domain: linear interpolation of unit normals ≤ 90° apart.
                prop_assert!(p.k >= 0.499 && p.k <= 1.0 + 1e-9, "K = {}", p.k);
            }
            Ok(())
        },
    );
}

#[test]
fn diagonal_increment_is_the_sum_of_horizontal_and_vertical() {
    use golden::units::normalizer;
    // A steep and a shallow working edge: between them the walks use every step type.
    let steep = simple_triangle();
    let shallow = ScreenTriangle {
        v: [
            vertex(10, 5, DVec3::new(-0.10, 0.45, 0.89)),
            vertex(90, 25, DVec3::new(0.05, 0.30, 0.95)),
            vertex(20, 20, DVec3::new(-0.12, 0.22, 0.97)),
        ],
        frac: 0,
    };
    let mut steps = Vec::new();
    for tri in [steep, shallow] {
        let walk = raster::walk(&tri);
        let s = normalizer::setup(&tri, &walk).unwrap();
        assert!((s.delta_d(1) - (s.delta_h + s.delta_v)).length() < 1e-15);
        assert!((s.delta_d(-1) - (s.delta_v - s.delta_h)).length() < 1e-15);
        let pixels = normalizer::interpolate(&s, &walk);
        let plane = tri.normal_plane().unwrap();
        for p in &pixels {
            assert!((p.n - plane.at_pixel(p.x, p.y)).length() < 1e-12);
        }
        steps.extend(
            walk.rows
                .iter()
                .flat_map(|r| r.edge_steps.iter().map(|e| e.step)),
        );
    }
    for t in [
        golden::StepType::Horizontal,
        golden::StepType::Vertical,
        golden::StepType::Diagonal,
    ] {
        assert!(
            steps.contains(&t),
            "no {t:?} step: the test would not exercise it"
        );
    }
}

// ---------------------------------------------------------------- Gouraud

#[test]
fn gouraud_planes_pass_through_the_vertex_intensities() {
    use golden::shading::gouraud;
    on_random_setups(
        "gouraud_planes_through_vertices",
        gouraud::setup,
        |tri, ctx, s| {
            let vertices = tri.v.map(|v| ((v.x as f64, v.y as f64), v.normal));
            passes_through(ctx, vertices, |c, x, y| {
                let p = &s.planes[c];
                p.a * x + p.b * y + p.c
            })?;
            for (i, v) in tri.v.iter().enumerate() {
                for (c, want) in ctx.exact_intensity(v.normal).into_iter().enumerate() {
                    prop_assert!((s.vertex[i][c] - want).abs() < 1e-9);
                }
            }
            Ok(())
        },
    );
}

// ---------------------------------------------------------------- quadric (§8)

#[test]
fn quadric_fits_the_six_nodes_and_forward_differences_match_the_direct_form() {
    use golden::shading::quadric;
    on_random_setups(
        "quadric_nodes_and_forward_differences",
        quadric::setup,
        |tri, ctx, s| {
            passes_through(ctx, quadric::nodes(tri), |c, x, y| {
                quadric::direct(&s.coeffs[c], x, y)
            })?;
            for row in raster::walk(tri).rows.iter().filter(|r| r.len > 0) {
                for c in 0..3 {
                    let fd = quadric::row_kernel(&s, c, row);
                    for (i, x) in golden::methods::row_xs(row).enumerate() {
                        let d = quadric::direct(
                            &s.coeffs[c],
                            x as f64 + 0.5 - s.origin.0,
                            row.y as f64 + 0.5 - s.origin.1,
                        );
                        prop_assert!(
                            (fd[i] - d).abs() < 1e-6,
                            "row {} pixel {}: {} vs {}",
                            row.y,
                            i,
                            fd[i],
                            d
                        );
                    }
                }
            }
            Ok(())
        },
    );
}

// ---------------------------------------------------------------- cubic (§9)

#[test]
fn cubic_coefficients_interpolate_the_four_samples() {
    use golden::shading::cubic;
    runner("cubic_interpolates_samples", 1000)
        .run(
            &(0.0f64..300.0, 0.0f64..300.0, 0.0f64..300.0, 0.0f64..300.0),
            |(i1, i2, i3, i4)| {
                // With an exact 1/3 both groupings pass through the samples.
                for k in [
                    cubic::coefficients(i1, i2, i3, i4, 1.0 / 3.0),
                    cubic::coefficients_as_printed(i1, i2, i3, i4, 1.0 / 3.0),
                ] {
                    for (p, want) in [(0.0, i1), (1.0, i2), (0.5, i3), (0.25, i4)] {
                        prop_assert!((cubic::horner(&k, p) - want).abs() < 1e-9);
                    }
                }
                // With the shift-add 1/3 (our grouping) the error is 0.78% of the A and C terms only.
                let k = cubic::coefficients(i1, i2, i3, i4, cubic::THIRD);
                let exact = cubic::coefficients(i1, i2, i3, i4, 1.0 / 3.0);
                let bound = (cubic::THIRD * 3.0 - 1.0) * (exact[0].abs() + exact[2].abs()) + 1e-9;
                for p in [0.0, 0.25, 0.5, 0.75, 1.0] {
                    prop_assert!((cubic::horner(&k, p) - cubic::horner(&exact, p)).abs() <= bound);
                }
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn printed_grouping_of_the_third_breaks_a_constant_intensity() {
    use golden::shading::cubic;
    let i = 200.0;
    let ours = cubic::coefficients(i, i, i, i, cubic::THIRD);
    let printed = cubic::coefficients_as_printed(i, i, i, i, cubic::THIRD);
    assert_eq!(cubic::horner(&ours, 1.0), i);
    // A = 72·I·(43/128) − 24·I = 0.1875·I, C = 33·I·(43/128) − 11·I ≈ 0.0859·I: 27% at p = 1.
    let rel = cubic::horner(&printed, 1.0) / i - 1.0;
    assert!((rel - (0.1875 + 11.0 / 128.0)).abs() < 1e-12, "{rel}");
}

// ---------------------------------------------------------------- angular (§4)

/// Independent computation: the normal turning at constant angular rate from N_A to N_B
/// (slerp), dotted with X.
#[test]
fn angular_kernel_is_x_dot_slerp() {
    use golden::shading::angular;
    let strat = (
        near(DVec3::Z),
        near(DVec3::Z),
        near(DVec3::new(0.3, 0.6, 0.7).normalize()),
        0u32..80,
    );
    runner("angular_kernel_is_x_dot_slerp", 1000)
        .run(&strat, |(na, nb, x, m)| {
            let got = angular::span_kernel(&angular::span_setup(na, nb, x, m));
            prop_assert_eq!(got.len(), m as usize + 1);
            let phi = na.dot(nb).clamp(-1.0, 1.0).acos();
            for (t, g) in got.iter().enumerate() {
                let n = if phi < 1e-9 || m == 0 {
                    na
                } else {
                    let u = t as f64 / m as f64;
                    (na * ((1.0 - u) * phi).sin() + nb * (u * phi).sin()) / phi.sin()
                };
                prop_assert!(
                    (g - n.dot(x)).abs() < 1e-9,
                    "t = {}: {} vs {}",
                    t,
                    g,
                    n.dot(x)
                );
            }
            Ok(())
        })
        .unwrap();
}

// ---------------------------------------------------------------- W(n, γ) (§2)

#[test]
fn w_is_exact_when_k_equals_n_and_zero_past_its_root() {
    use golden::shading::brdf;
    for k in brdf::KS {
        for c in [1.0, 0.999, 0.99, 0.9, 0.5, 0.1] {
            assert!((brdf::w_exact(k, k, c) - c.powi(k as i32)).abs() < 1e-12);
        }
        // The bracket 1 − a(1 − c) is negative below c = 1 − 1/a: W = 0 there.
        let a = brdf::slope(1000, k, true);
        assert_eq!(brdf::w_kernel(a, k, 1.0 - 1.5 / a), 0.0);
        assert_eq!(brdf::w_kernel(a, k, 1.0), 1.0);
    }
}

// ---------------------------------------------------------------- bump (§2)

#[test]
fn bump_perturbation_matches_the_angle_sum_within_the_prom_error() {
    use golden::shading::bump::{self, BumpMap, SinProm};
    let map = BumpMap::default();
    let prom = SinProm {
        addr_bits: bump::SIN_PHI_ADDR_BITS,
        interp_bits: 0,
    };
    let top = ((1u32 << bump::CODE_BITS) - 1) as f64;
    // PROM address: |c − c'| ≤ 1/(2·top) moves √(1 − c²) by at most √(2·|c − c'|) = √(1/top);
    // every PROM word (sin γ, cos dγ, sin dγ) is rounded to Q1.15: ≤ 2⁻¹⁶ each.
    let sin_err = (1.0 / prom.top()).sqrt();
    let word_err = 3.0 * (-16f64).exp2();
    runner("bump_matches_angle_sum", 2000)
        .run(
            &(0.0f64..std::f64::consts::FRAC_PI_2, 0i32..64, 0i32..64),
            |(g, x, y)| {
                let code = map.code(x, y);
                let dg = map.d_gamma(x, y);
                let dq = code.magnitude as f64 / top
                    * map.amplitude
                    * if code.negative { -1.0 } else { 1.0 };
                prop_assert!((dq - dg).abs() <= map.amplitude / (2.0 * top) + 1e-15);
                let got = bump::perturb(g.cos(), code, &map, &prom);
                let want = (g + dq).cos();
                prop_assert!(
                    (got - want).abs() <= dq.abs().sin() * sin_err + word_err + 1e-12,
                    "{} vs {}",
                    got,
                    want
                );
                Ok(())
            },
        )
        .unwrap();
    // A zero code leaves the cosine untouched.
    let zero = bump::Code {
        negative: false,
        magnitude: 0,
    };
    assert_eq!(bump::perturb(0.8, zero, &map, &prom), 0.8);
}

// ---------------------------------------------------------------- the thesis sphere

/// Must-show of issue 2 at the golden level (the lead's end-to-end test checks the rendered
/// files): on the default scene, normalizer-fit ≤ 0.0001 and fast-fit, angular, quadric, cubic,
/// brdf-k16 ≤ 0.00025 against the reference. The published forms are printed as measured.
#[test]
fn sphere_nmse_default_scene() {
    let table = sphere_nmse(50, 50, 90.0, LightingModel::Blinn);
    for (m, v) in &table {
        println!(
            "{:16} {:.3e}  {}",
            m.name(),
            v,
            golden::nmse::Band::of(*v).label()
        );
    }
    assert_issue_2_bounds(&table, "Blinn");
    let get = |m: Method| nmse_of(&table, m);
    // The published forms are visibly worse than their fits (SPEC §10), and flat is worst of all.
    assert!(get(Method::Normalizer) > 10.0 * get(Method::NormalizerFit));
    assert!(get(Method::Fast) > 10.0 * get(Method::FastFit));
    // The piecewise normalizer is within 1.13e-4 of 1/√K on the whole domain (FIT: 0.82 %).
    assert!(
        get(Method::NormalizerPw) <= 0.0001,
        "normalizer-pw {}",
        get(Method::NormalizerPw)
    );
    assert!(get(Method::Flat) > get(Method::Gouraud));
}

/// The same bounds hold with the Phong and Lambert lighting models.
#[test]
fn sphere_nmse_other_lighting_models() {
    for lighting in [LightingModel::Phong, LightingModel::Lambert] {
        let table = sphere_nmse(50, 50, 90.0, lighting);
        for (m, v) in &table {
            println!("{lighting:?} {:16} {:.3e}", m.name(), v);
        }
        assert_issue_2_bounds(&table, &format!("{lighting:?}"));
    }
}

/// Why the fit is exact in value *and slope* at K = 1: against the alternative of the same cost
/// that is exact in value only and minimax over [0.499, 1] (max error 0.377% instead of 0.823%),
/// the tangent fit gives the lower NMSE on coarse and fine spheres, dull and shiny.
#[test]
fn tangent_fit_beats_value_only_minimax_on_spheres() {
    use golden::units::normalizer;
    // Value-only minimax: f = 1 + d·u + c·u², u = K − 1, found by a nested search (see report).
    let (d, c) = (-0.4220610653335927f64, 0.7922035433590682f64);
    let value_only = [c, d - 2.0 * c, 1.0 - d + c];
    assert!((normalizer::scale(1.0, value_only) - 1.0).abs() < 1e-15);
    for rez in [10u32, 50] {
        for n in [50u32, 255] {
            let size = 400;
            let tris = sphere_scene(rez, size);
            let ctx = ctx_for(n, 90.0, LightingModel::Blinn);
            let reference = render(&tris, Method::Reference, &ctx, size, size);
            let nmse_of = |co: golden::units::normalizer::Coeffs| {
                let rgb = render_with(&tris, size, size, |tri, walk, emit| {
                    normalizer::shade(tri, walk, &ctx, co, emit)
                });
                golden::nmse::nmse(&reference, &rgb)
            };
            let (t, v) = (nmse_of(normalizer::FIT), nmse_of(value_only));
            println!("rez {rez} n {n}: tangent fit {t:.2e}, value-only minimax {v:.2e}");
            assert!(t < v, "rez {rez} n {n}: {t} vs {v}");
        }
    }
}

/// The textured methods light the texel as `normalizer-fit` lights the material: with every
/// corner's texture coordinate inside one texel, each textured method's colour is
/// `normalizer-fit`'s with that texel as the diffuse colour, pixel for pixel.
#[test]
fn textured_methods_light_the_texel() {
    let tex = golden::texture::Texture::builtin();
    // Texel (12, 4) of the built-in texture (a dark checker square), its centre in (s, t).
    let st = glam::DVec2::new(12.5 / 256.0, 4.5 / 256.0);
    let mut tri = simple_triangle();
    for v in &mut tri.v {
        v.uv = st;
    }
    let texel = tex.texel(12, 4);
    assert_ne!(texel.map(f64::from), Material::default().diffuse);
    for lighting in lightings() {
        let ctx = ShadeContext {
            lighting,
            ..ShadeContext::default()
        };
        let mut lit = ctx;
        lit.material.diffuse = texel.map(f64::from);
        let want = shade(Method::NormalizerFit, &tri, &lit);
        assert!(want.len() > 300);
        for m in std::iter::once(Method::TextureReference).chain(Method::TEXTURED) {
            assert_eq!(shade(m, &tri, &ctx), want, "{m} {lighting:?}");
        }
    }
}
