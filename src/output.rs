//! Image output. STUB: being written (placeholder type so the renderer compiles).
/// Linear RGB image, row-major, top row first.
pub struct ImageRgb {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Pixels.
    pub data: Vec<glam::Vec3>,
}
