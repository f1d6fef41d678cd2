//! PNG files of 8-bit greyscale and RGB rasters (map pictures, figures), encoded with one fixed
//! set of settings (fast deflate, an adaptive filter per row), so that the same pixels always
//! give the same bytes.

/// The channels of a raster handed to [`encode`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channels {
    /// One byte per pixel.
    Grey,
    /// Three bytes per pixel: red, green, blue.
    Rgb,
}

impl Channels {
    fn bytes_per_pixel(self) -> usize {
        match self {
            Channels::Grey => 1,
            Channels::Rgb => 3,
        }
    }
}

/// `pixels` (row by row from the top, `width × height` pixels of `channels`) as a PNG file.
/// Fails when the buffer's length does not match the size, or the size is zero.
pub fn encode(pixels: &[u8], width: u32, height: u32, channels: Channels) -> Result<Vec<u8>, String> {
    let wanted = width as usize * height as usize * channels.bytes_per_pixel();
    if pixels.len() != wanted {
        return Err(format!("{} bytes for a {width} × {height} raster of {wanted} bytes", pixels.len()));
    }
    let mut out = Vec::new();
    let mut encoder =
        png::Encoder::with_info(&mut out, png::Info::with_size(width, height)).map_err(|e| e.to_string())?;
    encoder.set_color(match channels {
        Channels::Grey => png::ColorType::Grayscale,
        Channels::Rgb => png::ColorType::Rgb,
    });
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(pixels).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_raster_round_trips_through_the_decoder() {
        let pixels: Vec<u8> = (0..6 * 4 * 3).map(|i| (i * 7 % 256) as u8).collect();
        let file = encode(&pixels, 6, 4, Channels::Rgb).unwrap();
        let back = image::load_from_memory(&file).unwrap().to_rgb8();
        assert_eq!((back.width(), back.height()), (6, 4));
        assert_eq!(back.into_raw(), pixels);
    }

    #[test]
    fn a_buffer_of_the_wrong_length_is_refused() {
        assert!(encode(&[0; 5], 2, 2, Channels::Grey).unwrap_err().contains("5 bytes"));
        assert!(encode(&[0; 4], 2, 2, Channels::Grey).is_ok());
    }
}
