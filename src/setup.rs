//! Scene set-up shared by every command: mesh, camera, projection to 12-bit screen addresses,
//! light, viewer and material. This is the "software side" that also drives the RTL engine.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use glam::{DQuat, DVec3};
use golden::scene::{self, Camera};
use golden::shade::{LightingModel, Material, ShadeContext};
use golden::texture::Texture;
use golden::ScreenTriangle;

/// Lighting model for every method (`--lighting`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Lighting {
    Blinn,
    Phong,
    Lambert,
}

impl From<Lighting> for LightingModel {
    fn from(l: Lighting) -> LightingModel {
        match l {
            Lighting::Blinn => LightingModel::Blinn,
            Lighting::Phong => LightingModel::Phong,
            Lighting::Lambert => LightingModel::Lambert,
        }
    }
}

/// Scene options shared by `render`, `sweep` and the RTL commands. Defaults are the thesis
/// prototype's: sphere, tessellation 50, shininess 50, light at 90°.
#[derive(clap::Args, Debug, Clone, serde::Serialize)]
pub struct SceneArgs {
    /// `sphere`, `torus`, `plane` (a textured ground plane receding to the horizon, through a
    /// perspective camera), or the path of a Wavefront .obj mesh (any path the system accepts,
    /// UTF-8 or not; its `vt` texture coordinates are read).
    #[arg(long, default_value = "sphere")]
    #[serde(serialize_with = "lossy_path")]
    pub scene: PathBuf,
    /// Tessellation of the procedural sphere / torus (the prototype's "Sphere Rez").
    #[arg(long, default_value_t = 50, value_parser = clap::value_parser!(u32).range(3..=100))]
    pub rez: u32,
    /// Specular exponent n.
    #[arg(long, default_value_t = 50, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub shininess: u32,
    /// Light direction in degrees, 0..=360 (90 = from the front).
    #[arg(
        long = "light-deg",
        default_value_t = 90.0,
        allow_negative_numbers = true
    )]
    pub light_deg: f64,
    /// Canvas size WxH, each 1..=4096 (screen addresses are 12 bits).
    #[arg(long, default_value = "400x400", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Lighting model used by the reference and every method.
    #[arg(long, value_enum, default_value = "blinn")]
    pub lighting: Lighting,
    /// Adaptive subdivision of the projected mesh before every method (set-up software,
    /// `golden::shading::refine`): 0 (off), 1 or 2 levels of midpoint splits of every interior edge,
    /// or auto (split edges whose normals are more than 15° apart, up to 4 levels). The
    /// reference is always the undivided mesh.
    #[arg(long, default_value = "0")]
    pub subdivide: golden::shading::refine::Subdivide,
    /// Fraction bits of the projected vertex coordinates: 4 (1/16 pixel, the default: the
    /// walks, set-ups and `--subdivide` midpoints on the finer grid, for the reference and
    /// every method, golden and RTL) or 0 (integer 12-bit addresses).
    #[arg(long, default_value_t = golden::SUBPIXEL_BITS, value_parser = parse_subpixel)]
    pub subpixel: u32,
    /// The texture the textured methods read: a PNG of power-of-two sides from 1 to 1024 texels
    /// (8-bit; grey or alpha channels are converted to RGB, alpha ignored), wrapped with GL_REPEAT,
    /// (s, t) = (0, 0) at its bottom-left corner. Default: the built-in 256×256 checkerboard with
    /// a coloured grid.
    #[arg(long)]
    #[serde(serialize_with = "lossy_opt_path")]
    pub texture: Option<PathBuf>,
    /// A perspective camera: the eye this many bounding-sphere radii from the scene's centre
    /// (a number above 1; smaller is stronger perspective), the projected scene fitted to the
    /// canvas. Only positions and texture coordinates see the perspective (the viewer of the
    /// shading stays at infinity, V = +z). Default: orthographic for `sphere`, `torus` and OBJ
    /// meshes; `plane`'s own camera (1.1 radii).
    #[arg(long, value_parser = parse_eye, allow_negative_numbers = true)]
    pub eye: Option<f64>,
}

/// Parse `--eye`: a finite number above 1 (the eye outside the bounding sphere).
pub(crate) fn parse_eye(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(r) if r.is_finite() && r > 1.0 && r <= 1e6 => Ok(r),
        _ => Err(format!(
            "eye {s:?}: expected a number above 1 and at most 1e6 (bounding-sphere radii from the centre)"
        )),
    }
}

/// Parse `--subpixel`: 0 or [`golden::SUBPIXEL_BITS`].
pub(crate) fn parse_subpixel(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(0) => Ok(0),
        Ok(n) if n == golden::SUBPIXEL_BITS => Ok(n),
        _ => Err(format!(
            "subpixel {s:?}: expected 0 (integer vertices) or {} (the address block's fraction bits)",
            golden::SUBPIXEL_BITS
        )),
    }
}

impl Default for SceneArgs {
    fn default() -> Self {
        SceneArgs {
            scene: "sphere".into(),
            rez: 50,
            shininess: 50,
            light_deg: 90.0,
            size: (400, 400),
            lighting: Lighting::Blinn,
            subdivide: golden::shading::refine::Subdivide::OFF,
            subpixel: golden::SUBPIXEL_BITS,
            texture: None,
            eye: None,
        }
    }
}

/// Parse `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("size {s:?} is not WxH (e.g. 400x400)"))?;
    let dim = |v: &str| -> Result<u32, String> {
        let n: u32 = v
            .trim()
            .parse()
            .map_err(|_| format!("size {s:?}: {v:?} is not a whole number"))?;
        if !(1..=4096).contains(&n) {
            return Err(format!(
                "size {s:?}: {n} is outside 1..=4096 (screen addresses are 12 bits)"
            ));
        }
        Ok(n)
    };
    Ok((dim(w)?, dim(h)?))
}

/// Everything a renderer needs.
pub struct Setup {
    /// The triangles every method renders (after `--subdivide`).
    pub tris: Vec<ScreenTriangle>,
    /// The undivided mesh: what the reference renders.
    pub base: Vec<ScreenTriangle>,
    pub ctx: ShadeContext,
    pub width: u32,
    pub height: u32,
    /// The texture the textured methods read (`--texture`, or the built-in one).
    pub texture: Texture,
    /// Whether the mesh has texture coordinates (the procedural scenes do; an OBJ file when it
    /// has `vt`).
    pub textured_mesh: bool,
}

impl Setup {
    /// The scene the hardware renders: the triangles, shading, canvas and texture.
    pub fn scene(&self) -> pipeline::render::Scene<'_> {
        pipeline::render::Scene {
            tris: &self.tris,
            ctx: &self.ctx,
            width: self.width,
            height: self.height,
            texture: Some(&self.texture),
        }
    }
}

fn lossy_path<S: serde::Serializer>(p: &Path, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_str(&p.to_string_lossy())
}

fn lossy_opt_path<S: serde::Serializer>(
    p: &Option<PathBuf>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    match p {
        Some(p) => s.serialize_str(&p.to_string_lossy()),
        None => s.serialize_none(),
    }
}

/// Largest texture PNG file read (bytes): a 1024×1024 RGB8 image, uncompressed, with room.
const MAX_TEXTURE_BYTES: u64 = 16 << 20;

/// Read the texture PNG `path`: a regular file of at most 16 MiB, a PNG whose sides are powers
/// of two from 1 to 1024 (checked from its header, before decoding), decoded to RGB8.
pub fn load_texture(path: &Path) -> Result<Texture> {
    use golden::scene::SceneError;
    let shown = path.display();
    let bytes = golden::scene::read_regular_file(path, MAX_TEXTURE_BYTES).map_err(|e| match e {
        SceneError::ObjMissing { .. } => anyhow::anyhow!("texture file {shown} not found"),
        SceneError::ObjUnreadable { reason, .. } => {
            anyhow::anyhow!("texture file {shown} cannot be read: {reason}")
        }
        e => anyhow::anyhow!("texture file {shown}: {e}"),
    })?;
    let reader = || {
        image::ImageReader::with_format(std::io::Cursor::new(&bytes[..]), image::ImageFormat::Png)
    };
    let bad =
        |e: image::ImageError| anyhow::anyhow!("texture file {shown} is not a readable PNG: {e}");
    let (width, height) = reader().into_dimensions().map_err(bad)?;
    let side_ok = |n: u32| n.is_power_of_two() && n <= golden::texture::MAX_TEXTURE_SIDE;
    if !side_ok(width) || !side_ok(height) {
        bail!(
            "texture file {shown} is {width}x{height}: each side must be a power of two from 1 to {}",
            golden::texture::MAX_TEXTURE_SIDE
        );
    }
    let mut r = reader();
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(golden::texture::MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(golden::texture::MAX_TEXTURE_SIDE);
    limits.max_alloc = Some(64 << 20);
    r.limits(limits);
    let img = r.decode().map_err(bad)?.to_rgb8();
    let rgb = img.pixels().map(|p| p.0).collect();
    Texture::new(width, height, rgb).map_err(|e| anyhow::anyhow!("texture file {shown}: {e}"))
}

impl Setup {
    /// An error when a textured method is asked for a scene it cannot texture: a mesh without
    /// texture coordinates, or a triangle beyond the texture-coordinate block's range.
    pub fn check_textured(&self, methods: &[golden::methods::Method], scene: &Path) -> Result<()> {
        let Some(m) = methods.iter().find(|m| m.is_textured()) else {
            return Ok(());
        };
        if !self.textured_mesh {
            bail!(
                "method {m} needs texture coordinates, and scene {} has none (an OBJ file gives them with `vt` lines)",
                scene.display()
            );
        }
        if let Some(e) = golden::shading::texture::range_error(&self.tris, &self.texture) {
            bail!("scene {}: {e}", scene.display());
        }
        Ok(())
    }

    /// An error unless some front-facing triangle covers a pixel of the canvas: a scene that
    /// draws nothing would report every method "identical" on a black image (`render`,
    /// `sweep`) or stream no triangle (`stream`). Empty work is an error everywhere.
    pub fn ensure_drawn(&self) -> Result<()> {
        let covered = golden::render::render(
            &self.tris,
            golden::methods::Method::Flat,
            &self.ctx,
            self.width,
            self.height,
        )
        .fragments;
        if covered.iter().all(|&n| n == 0) {
            bail!(
                "nothing to draw: no front-facing triangle of the scene covers a pixel of the {}x{} canvas",
                self.width,
                self.height
            );
        }
        Ok(())
    }
}

impl SceneArgs {
    /// The scene is an OBJ file (its name ends in `.obj`, any case).
    pub fn is_obj(&self) -> bool {
        self.scene
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
    }

    /// One line for reports: the scene, and its tessellation when it is procedural.
    pub fn describe(&self) -> String {
        let sub = match self.subdivide {
            golden::shading::refine::Subdivide::Levels(0) => String::new(),
            s => format!(" subdivide {s}"),
        } + &match self.subpixel {
            golden::SUBPIXEL_BITS => String::new(),
            f => format!(" subpixel {f}"),
        };
        if self.is_obj() {
            format!("scene {}{sub}", self.scene.display())
        } else {
            format!("scene {} rez {}{sub}", self.scene.display(), self.rez)
        }
    }
}

/// Build the scene described by `args`.
pub fn build(args: &SceneArgs) -> Result<Setup> {
    let (width, height) = args.size;
    let mut perspective = false;
    let (mesh, rotation) = match args.scene.to_str() {
        Some("sphere") => (scene::uv_sphere(args.rez)?, DQuat::IDENTITY),
        Some("torus") => (
            scene::torus(args.rez)?,
            DQuat::from_rotation_x(55f64.to_radians()),
        ),
        Some("plane") => {
            // Its perspective camera: `Camera::plane_view`.
            perspective = true;
            (scene::plane(args.rez)?, DQuat::IDENTITY)
        }
        _ if args.is_obj() => {
            let (mesh, fallbacks) = scene::load_obj_counting(&args.scene)?;
            if fallbacks > 0 {
                let (n, verb) = if fallbacks == 1 {
                    ("vertex", "gets")
                } else {
                    ("vertices", "get")
                };
                eprintln!(
                    "warning: OBJ file {}: {fallbacks} {n} whose faces' normals cancel {verb} the normal of its first face",
                    args.scene.display()
                );
            }
            (mesh, DQuat::IDENTITY)
        }
        _ => bail!(
            "unknown scene {:?}: expected `sphere`, `torus`, `plane` or the path of a .obj file",
            args.scene.display().to_string()
        ),
    };
    let camera = match (args.eye, perspective) {
        (Some(r), true) => Camera::plane_view_at(&mesh, width, height, r),
        (None, true) => Camera::plane_view(&mesh, width, height),
        (Some(r), false) => Camera::fit_perspective(&mesh, width, height, rotation, r),
        (None, false) => Camera::fit(&mesh, width, height, rotation),
    };
    let textured_mesh = !mesh.uvs.is_empty();
    let texture = match &args.texture {
        Some(p) => load_texture(p)?,
        None => Texture::builtin().clone(),
    };
    let base = scene::project_subpixel(&mesh, &camera, width, height, args.subpixel)
        .with_context(|| format!("projecting scene {:?}", args.scene))?;
    let tris = golden::shading::refine::refine(&base, args.subdivide);
    let light = scene::light_direction(args.light_deg)?;
    let ctx = ShadeContext::new(
        Material {
            shininess: args.shininess,
            ..Material::default()
        },
        args.lighting.into(),
        light,
        DVec3::Z,
    )?;
    Ok(Setup {
        tris,
        base,
        ctx,
        width,
        height,
        texture,
        textured_mesh,
    })
}
