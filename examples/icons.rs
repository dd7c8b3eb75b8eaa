//! Writes the bot's eight icons side by side, magnified 8 times, to `icons.png`.
use botsim::regs::Orientation;
use botsim::render::display::{icon, icon_colour};

fn main() {
    let (w, h) = (8 * 16 * 8 + 7 * 8, 16 * 8);
    let mut rgb = vec![255u8; w * h * 3];
    for (n, o) in Orientation::ALL.into_iter().enumerate() {
        let ic = icon(o);
        for y in 0..h {
            for x in 0..16 * 8 {
                let v = ic[y / 8][x / 8];
                if v != 0 {
                    let i = (y * w + n * (16 * 8 + 8) + x) * 3;
                    rgb[i..i + 3].copy_from_slice(&icon_colour(v));
                }
            }
        }
    }
    let mut out = Vec::new();
    {
        let mut e = png::Encoder::new(&mut out, w as u32, h as u32);
        e.set_color(png::ColorType::Rgb);
        e.write_header().unwrap().write_image_data(&rgb).unwrap();
    }
    std::fs::write("icons.png", out).unwrap();
}
