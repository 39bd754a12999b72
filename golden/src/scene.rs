//! Scenes, by concern:
//!
//! | module | what |
//! |---|---|
//! | [`mesh`] | the [`Mesh`] type and its checks, procedural UV sphere, torus and ground plane |
//! | [`obj`] | Wavefront OBJ meshes through `tobj`, smooth normals where the file has none |
//! | [`camera`] | the [`Camera`] fitted to a mesh, orthographic or perspective |
//! | [`projection`] | [`project`] with back-face culling, the light |
//! | [`snap`] | [`screen_addresses`]: rounding to integer addresses with the fold repair |
//!
//! Every public item is re-exported here, so `scene::X` names it whatever module it lives in;
//! [`SceneError`] is shared by all four.

pub mod camera;
pub mod mesh;
pub mod obj;
pub mod projection;
pub mod snap;

pub use camera::{Camera, PLANE_ELEVATION_DEG, PLANE_EYE_RADII, PLANE_YAW_DEG};
pub use mesh::{
    plane, torus, uv_sphere, Mesh, PLANE_DEPTH, PLANE_HALF_WIDTH, REZ_RANGE, TORUS_MAJOR,
    TORUS_MINOR,
};
pub use obj::{
    load_obj, load_obj_counting, read_regular_file, BYTES_PER_TRIANGLE, BYTES_PER_VERTEX,
    MAX_COORDINATE, MAX_OBJ_BYTES, MAX_TRIANGLES, MAX_VERTICES, MEMORY_BUDGET_BYTES, MIN_EXTENT,
};
pub use projection::{light_direction, project, project_subpixel, LIGHT_ELEVATION_DEG, MAX_CANVAS};
pub use snap::screen_addresses;

/// Everything that can go wrong building or projecting a scene. Messages are one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("{shape} rez {rez} is outside the allowed range 3..=100")]
    Rez { shape: &'static str, rez: u32 },
    #[error("light angle {0}° is outside the allowed range 0..=360")]
    LightAngle(f64),
    #[error("OBJ file {path} not found")]
    ObjMissing { path: String },
    #[error("OBJ file {path} cannot be read: {reason}")]
    ObjUnreadable { path: String, reason: String },
    #[error("OBJ file {path} is malformed: {reason}")]
    ObjMalformed { path: String, reason: String },
    #[error("OBJ file {path} holds no triangles")]
    ObjEmpty { path: String },
    #[error("{origin}: normals are given for {normals} of {vertices} vertices (all or none)")]
    NormalCount {
        origin: String,
        normals: usize,
        vertices: usize,
    },
    #[error("{origin}: vertex {vertex} has a non-finite coordinate {value}")]
    BadPosition {
        origin: String,
        vertex: usize,
        value: f64,
    },
    #[error("{origin}: vertex {vertex} has a coordinate {value:e}, beyond the range ±{max:e} (the camera fit squares distances)")]
    CoordinateRange {
        origin: String,
        vertex: usize,
        value: f64,
        max: f64,
    },
    #[error("{origin}: the mesh's extent {extent:e} is too small to fit a camera to (its largest coordinate is {largest:e}; the extent must be at least 1e-30 and 1e-9 of that): scale the mesh up or move it to the origin")]
    Extent {
        origin: String,
        extent: f64,
        largest: f64,
    },
    #[error("{origin}: vertex {vertex} has a {problem} normal")]
    BadNormal {
        origin: String,
        vertex: usize,
        problem: &'static str,
    },
    #[error("{origin}: triangle {triangle} refers to vertex {index}, but there are {count}")]
    BadIndex {
        origin: String,
        triangle: usize,
        index: u32,
        count: usize,
    },
    #[error("{origin}: texture coordinates are given for {given} of {triangles} triangles (all or none)")]
    TexCoordCount {
        origin: String,
        given: usize,
        triangles: usize,
    },
    #[error("{origin}: triangle {triangle} has a non-finite texture coordinate")]
    BadTexCoord { origin: String, triangle: usize },
    #[error("{origin}: texture coordinate (vt) on line {line} is not finite: {text}")]
    BadVt {
        origin: String,
        line: usize,
        text: String,
    },
    #[error("{origin}: {positions} positions but {normals} normals")]
    Inconsistent {
        origin: String,
        positions: usize,
        normals: usize,
    },
    #[error("canvas {width}x{height} is empty")]
    CanvasEmpty { width: u32, height: u32 },
    #[error(
        "canvas {width}x{height} exceeds the 12-bit address range (at most 4096 pixels per side)"
    )]
    CanvasTooLarge { width: u32, height: u32 },
    #[error(
        "triangle {triangle}: vertex {vertex} projects to screen {axis} = {value}, outside the 12-bit address range 0..=4095"
    )]
    AddressRange {
        triangle: usize,
        vertex: u32,
        axis: char,
        value: f64,
    },
}
