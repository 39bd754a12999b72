//! Every family through its AXI4-Stream top and through its pipeline's ports draws the same
//! frame, bit for bit (colours, and depth where the hardware's z words decide it), in either
//! set-up order where the family has one; the stream top really ran (its set-up words cost
//! clocks the ports do not, where the lines or parents are short enough to show it). One table,
//! one loop: a family added to `pipeline::render` is one row here.

use golden::methods::Method;
use indicatif::ProgressBar;
use shadecore::rtl_engine::{render_rtl_with, Address, LitTop, RtlBuild, RtlRender, SetupOrder};
use shadecore::setup::{build, SceneArgs};

/// One row: a scene, the methods, the build beside the top, and whether the stream's clocks
/// must exceed the ports' (records longer than the walks they set up).
struct Case {
    scene: &'static str,
    rez: u32,
    size: u32,
    methods: &'static [Method],
    address: Address,
    horner_pipelined: bool,
    stream_slower: bool,
}

const CASES: &[Case] = &[
    // Lit: pixel-stream against pixel-pipeline.
    Case {
        scene: "sphere",
        rez: 16,
        size: 160,
        methods: &[Method::NormalizerFit, Method::BrdfK8],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: false,
    },
    // Texture: textured-stream against textured-pipeline (the stream sends the built-in
    // 256×256 texture as records, four clocks a texel; the ports write it uncounted).
    Case {
        scene: "sphere",
        rez: 16,
        size: 160,
        methods: &[Method::Texture],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: true,
    },
    // Gouraud: gouraud-stream against gouraud-raster.
    Case {
        scene: "sphere",
        rez: 50,
        size: 400,
        methods: &[Method::Gouraud],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: false,
    },
    // Span: angular-, fast-, quadric-stream against the span pipelines (lines shorter than
    // 27, 39 or 9 pixels are set-up bound: a line's record is 14, 20 or 5 words).
    Case {
        scene: "torus",
        rez: 50,
        size: 80,
        methods: &[Method::Angular, Method::Fast],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: true,
    },
    Case {
        scene: "sphere",
        rez: 50,
        size: 72,
        methods: &[Method::Quadric, Method::FastFit],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: true,
    },
    // Cubic: cubic-stream against cubic-pipeline, both Horner variants.
    Case {
        scene: "torus",
        rez: 50,
        size: 200,
        methods: &[Method::Cubic],
        address: Address::Default,
        horner_pipelined: false,
        stream_slower: false,
    },
    Case {
        scene: "torus",
        rez: 50,
        size: 200,
        methods: &[Method::Cubic],
        address: Address::Default,
        horner_pipelined: true,
        stream_slower: false,
    },
    // Four-triangle block: subdivision-stream against subdivision-raster (parents whose
    // longest lane walk is shorter than a 87-word record are set-up bound).
    Case {
        scene: "sphere",
        rez: 50,
        size: 400,
        methods: &[Method::Subdivision, Method::Gouraud],
        address: Address::FourTriangle,
        horner_pipelined: false,
        stream_slower: true,
    },
    Case {
        scene: "torus",
        rez: 50,
        size: 400,
        methods: &[Method::Subdivision, Method::Gouraud],
        address: Address::FourTriangle,
        horner_pipelined: false,
        stream_slower: true,
    },
];

#[test]
fn stream_tops_and_ports_render_the_same_frame() {
    for c in CASES {
        let s = build(&SceneArgs {
            scene: c.scene.into(),
            rez: c.rez,
            size: (c.size, c.size),
            ..SceneArgs::default()
        })
        .unwrap();
        for &method in c.methods {
            let run = |lit_top, setup_order| -> RtlRender {
                let b = RtlBuild {
                    lit_top,
                    setup_order,
                    address: c.address,
                    horner_pipelined: c.horner_pipelined,
                    ..RtlBuild::default()
                };
                render_rtl_with(&s, method, b, &ProgressBar::hidden()).unwrap()
            };
            let what = format!(
                "{method}, {} {}×{} ({:?}, pipelined Horner {})",
                c.scene, c.size, c.size, c.address, c.horner_pipelined
            );
            let stream = run(LitTop::Stream, SetupOrder::Balanced);
            let ports = run(LitTop::Pipeline, SetupOrder::Balanced);
            let mesh = run(LitTop::Stream, SetupOrder::Mesh);
            assert!(
                stream.stats.pixels > 1000,
                "{what}: a scene worth rendering"
            );
            for (label, other) in [("the pipeline's ports", &ports), ("mesh order", &mesh)] {
                assert_eq!(stream.stats.pixels, other.stats.pixels, "{what}: {label}");
                assert_eq!(
                    stream.stats.triangles, other.stats.triangles,
                    "{what}: {label}"
                );
                assert!(
                    stream.frame.rgb == other.frame.rgb,
                    "{what}: the stream top's frame and {label}'s differ"
                );
                assert!(
                    stream.frame.depth == other.frame.depth,
                    "{what}: depth differs from {label}'s"
                );
                assert_eq!(
                    stream.visibility_mismatches, other.visibility_mismatches,
                    "{what}: {label}"
                );
            }
            if c.stream_slower {
                assert!(stream.stats.clocks > ports.stats.clocks, "{what}");
            }
            println!(
                "{what}: stream top {} clocks ({:.3} px/clock; mesh order {}), ports {} ({:.3}), ratio {:.3}",
                stream.stats.clocks,
                stream.stats.pixels_per_clock(),
                mesh.stats.clocks,
                ports.stats.clocks,
                ports.stats.pixels_per_clock(),
                ports.stats.clocks as f64 / stream.stats.clocks as f64
            );
        }
    }
}
