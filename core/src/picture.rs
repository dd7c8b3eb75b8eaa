//! PNG encoding shared by the world files and the pictures.

/// Encode an 8-bit RGB image (`rgb.len() == width * height * 3`) as PNG bytes.
pub fn encode_rgb(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        // Writing to memory cannot fail except on a size mismatch, which is a bug here.
        let mut w = enc.write_header().expect("PNG header to memory");
        w.write_image_data(rgb).expect("PNG data matches the image size");
    }
    out
}
