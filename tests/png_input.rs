//! PNG files are untrusted input: a corpus of broken and unusual images (truncated, a bad
//! checksum, a header declaring a huge or empty image, non-PNG bytes, 16-bit, palette,
//! grey, interlaced) read by the library and by `splinescope diff`. Broken ones fail with a
//! clear error naming the file — never an abort, whatever the header declares — and every
//! valid colour type and depth reads as the RGBA pixels written into it.

mod common;

use std::path::PathBuf;

use splinescope_image::{ImageError, RgbaImage};
use splinescope_io::limits::LimitError;

use common::{
    PNG_SIGNATURE as SIGNATURE, crafted_png_header as crafted_header, encode_png,
    png_chunk as chunk, text,
};

fn dir(name: &str) -> PathBuf {
    let d = common::out_dir("png-input").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A 2×2 RGBA image in every pixel format PNG has, with the RGBA each must read as.
fn valid_corpus() -> Vec<(&'static str, Vec<u8>, Vec<u8>)> {
    use png::{BitDepth as D, ColorType as C};
    let rgba8 = [
        10, 20, 30, 255, 200, 100, 0, 128, 0, 0, 0, 0, 255, 255, 255, 255,
    ];
    let mut out = vec![(
        "rgba8",
        encode_png((2, 2), C::Rgba, D::Eight, &rgba8, None),
        rgba8.to_vec(),
    )];
    let rgb8 = [1, 2, 3, 4, 5, 6, 7, 8, 9, 250, 251, 252];
    out.push((
        "rgb8",
        encode_png((2, 2), C::Rgb, D::Eight, &rgb8, None),
        vec![1, 2, 3, 255, 4, 5, 6, 255, 7, 8, 9, 255, 250, 251, 252, 255],
    ));
    // 16-bit RGBA: big-endian samples; the high byte is kept.
    let rgba16: Vec<u8> = [0x1234_u16, 0xabcd, 0x00ff, 0xffff]
        .repeat(4)
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect();
    out.push((
        "rgba16",
        encode_png((2, 2), C::Rgba, D::Sixteen, &rgba16, None),
        [0x12, 0xab, 0x00, 0xff].repeat(4),
    ));
    let grey16: Vec<u8> = [0x8001_u16, 0x0000, 0xffff, 0x7f00]
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect();
    out.push((
        "grey16",
        encode_png((2, 2), C::Grayscale, D::Sixteen, &grey16, None),
        vec![
            0x80, 0x80, 0x80, 255, 0, 0, 0, 255, 255, 255, 255, 255, 0x7f, 0x7f, 0x7f, 255,
        ],
    ));
    // Palette of three colours, the second half transparent; 2 bits per index, rows
    // padded to a byte: row 0 = indices 0, 1; row 1 = indices 2, 1.
    let plte = [255, 0, 0, 0, 255, 0, 0, 0, 255];
    out.push((
        "palette2",
        encode_png(
            (2, 2),
            C::Indexed,
            D::Two,
            &[0b0001_0000, 0b1001_0000],
            Some((&plte, &[255, 128])),
        ),
        vec![
            255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255, 0, 255, 0, 128,
        ],
    ));
    // 1-bit grey: row 0 = black, white; row 1 = white, black.
    out.push((
        "grey1",
        encode_png(
            (2, 2),
            C::Grayscale,
            D::One,
            &[0b0100_0000, 0b1000_0000],
            None,
        ),
        vec![
            0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255,
        ],
    ));
    out.push((
        "grey-alpha8",
        encode_png(
            (2, 2),
            C::GrayscaleAlpha,
            D::Eight,
            &[9, 255, 99, 0, 199, 50, 255, 255],
            None,
        ),
        vec![
            9, 9, 9, 255, 99, 99, 99, 0, 199, 199, 199, 50, 255, 255, 255, 255,
        ],
    ));
    // Adam7-interlaced 2×2 grey (the encoder writes no Adam7, so it is crafted): passes 1 (pixel 0,0), 6 (pixel 1,0) and 7 (row 1), each
    // scanline a filter byte 0 and its samples, stored uncompressed.
    let raw = [0u8, 11, 0, 22, 0, 33, 44];
    let mut z = vec![
        0x78,
        0x01,
        0x01,
        raw.len() as u8,
        0,
        !(raw.len() as u8),
        0xff,
    ];
    z.extend_from_slice(&raw);
    let adler = {
        let (mut a, mut b) = (1u32, 0u32);
        for &x in &raw {
            a = (a + u32::from(x)) % 65521;
            b = (b + a) % 65521;
        }
        (b << 16) | a
    };
    z.extend_from_slice(&adler.to_be_bytes());
    let mut interlaced = SIGNATURE.to_vec();
    interlaced.extend(chunk(b"IHDR", &[0, 0, 0, 2, 0, 0, 0, 2, 8, 0, 0, 0, 1]));
    interlaced.extend(chunk(b"IDAT", &z));
    interlaced.extend(chunk(b"IEND", &[]));
    out.push((
        "interlaced-grey8",
        interlaced,
        vec![
            11, 11, 11, 255, 22, 22, 22, 255, 33, 33, 33, 255, 44, 44, 44, 255,
        ],
    ));
    out
}

#[test]
fn every_colour_type_and_depth_reads_as_the_rgba_written() {
    let d = dir("valid");
    for (name, bytes, want) in valid_corpus() {
        let path = d.join(format!("{name}.png"));
        std::fs::write(&path, &bytes).unwrap();
        let image = RgbaImage::read_png(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((image.width, image.height), (2, 2), "{name}");
        assert_eq!(image.data, want, "{name}");
    }
}

/// The broken images and what their error must say.
fn broken_corpus() -> Vec<(&'static str, Vec<u8>, &'static str)> {
    let good = valid_corpus().remove(0).1;
    let mut bad_crc = good.clone();
    // The last byte of the IHDR chunk's CRC (8 signature + 4 length + 4 type + 13 data).
    bad_crc[8 + 4 + 4 + 13 + 3] ^= 0x5a;
    let mut bad_data_crc = good.clone();
    let n = bad_data_crc.len();
    // Inside IDAT's compressed bytes (before IEND's 12 bytes and IDAT's CRC).
    bad_data_crc[n - 12 - 4 - 2] ^= 0x01;
    vec![
        ("truncated", good[..good.len() / 2].to_vec(), "truncated"),
        ("header-only", good[..20].to_vec(), "truncated"),
        (
            "bad-crc",
            bad_crc,
            "CRC checksum does not match in the IHDR chunk",
        ),
        (
            "bad-data-crc",
            bad_data_crc,
            "CRC checksum does not match in the IDAT chunk",
        ),
        (
            "huge-ihdr",
            crafted_header(100_000, 100_000),
            "SPLINESCOPE_MAX_IMAGE_PIXELS",
        ),
        (
            "wide-ihdr",
            crafted_header(2_000_000_000, 1),
            "SPLINESCOPE_MAX_IMAGE_PIXELS",
        ),
        ("zero-width", crafted_header(0, 10), "dimensions"),
        ("zero-height", crafted_header(10, 0), "dimensions"),
        ("empty-file", Vec::new(), "truncated"),
        ("json", b"{\"version\": 1}".to_vec(), "signature"),
        (
            "jpeg",
            vec![0xff, 0xd8, 0xff, 0xe0, 0, 16, b'J', b'F', b'I', b'F', 0],
            "signature",
        ),
        ("no-pixels", crafted_header(4, 4), "not a valid PNG"),
    ]
}

#[test]
fn broken_images_are_clear_errors_naming_the_file() {
    let d = dir("broken");
    for (name, bytes, says) in broken_corpus() {
        let path = d.join(format!("{name}.png"));
        std::fs::write(&path, &bytes).unwrap();
        let e = RgbaImage::read_png(&path)
            .map(|i| format!("{}×{}", i.width, i.height))
            .expect_err(name);
        let message = e.to_string();
        assert!(
            message.contains(&*path.to_string_lossy()),
            "{name}: the error names the file: {message}"
        );
        assert!(
            message.contains(says),
            "{name}: should say {says:?}: {message}"
        );
    }
}

#[test]
fn the_pixel_limit_is_read_from_the_header_and_named_with_its_variable() {
    let d = dir("limit");
    let path = d.join("huge.png");
    std::fs::write(&path, crafted_header(100_000, 100_000)).unwrap();
    match RgbaImage::read_png(&path) {
        Err(ImageError::TooLarge {
            width,
            height,
            limit: LimitError::Exceeded {
                found, limit, var, ..
            },
            ..
        }) => {
            assert_eq!((width, height), (100_000, 100_000));
            assert_eq!(found, 10_000_000_000);
            assert_eq!(limit, 1 << 26);
            assert_eq!(var, "SPLINESCOPE_MAX_IMAGE_PIXELS");
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    // 8192 × 8192 is the default limit itself: the header passes and the (absent) pixels
    // are what fails.
    std::fs::write(&path, crafted_header(8192, 8192)).unwrap();
    let e = RgbaImage::read_png(&path).unwrap_err();
    assert!(matches!(e, ImageError::Invalid { .. }), "{e}");
}

#[cfg(unix)]
#[test]
fn diff_refuses_every_broken_image_under_a_memory_cap() {
    let d = dir("cli");
    let good = d.join("good.png");
    std::fs::write(&good, valid_corpus().remove(0).1).unwrap();
    for (name, bytes, says) in broken_corpus() {
        let path = d.join(format!("{name}.png"));
        std::fs::write(&path, &bytes).unwrap();
        let out_png = d.join(format!("{name}.diff.png"));
        for args in [
            [path.as_path(), good.as_path()],
            [good.as_path(), path.as_path()],
        ] {
            // 1 GiB of address space: a decoder that believed the header would need 40 GB.
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg("ulimit -v 1048576; exec \"$0\" \"$@\"")
                .arg(env!("CARGO_BIN_EXE_splinescope"))
                .arg("diff")
                .args(args)
                .arg("-o")
                .arg(&out_png)
                .output()
                .unwrap();
            let all = text(&out);
            assert_eq!(out.status.code(), Some(1), "{name}: {all}");
            assert!(all.contains(says), "{name}: should say {says:?}: {all}");
            assert!(
                all.contains(&*path.to_string_lossy()),
                "{name}: names the file: {all}"
            );
            assert!(!out_png.exists(), "{name}: a failed diff writes nothing");
        }
    }
    // Raising the limit lets a large header through to the next check (its pixels).
    let big = d.join("huge-ihdr.png");
    let out = common::bin()
        .args(["diff", &big.to_string_lossy(), &good.to_string_lossy()])
        .env("SPLINESCOPE_MAX_IMAGE_PIXELS", "20000")
        .output()
        .unwrap();
    assert!(
        text(&out).contains("is over the limit of 20000"),
        "{}",
        text(&out)
    );
    // A variable that is not a whole number is refused, not replaced by the default.
    let out = common::bin()
        .args(["diff", &good.to_string_lossy(), &good.to_string_lossy()])
        .env("SPLINESCOPE_MAX_IMAGE_PIXELS", "1e9")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(
        text(&out).contains("SPLINESCOPE_MAX_IMAGE_PIXELS=\"1e9\" is not a whole number"),
        "{}",
        text(&out)
    );
}

#[test]
fn diff_compares_palette_and_16_bit_images_with_their_rgba_twins() {
    let d = dir("twins");
    for (name, bytes, want) in valid_corpus() {
        let a = d.join(format!("{name}.png"));
        std::fs::write(&a, &bytes).unwrap();
        let b = d.join(format!("{name}.rgba.png"));
        RgbaImage {
            width: 2,
            height: 2,
            data: want,
        }
        .write_png(&b)
        .unwrap();
        let out = common::run(&[
            "diff",
            &a.to_string_lossy(),
            &b.to_string_lossy(),
            "--tolerance",
            "channel=0,pixels=0",
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(0), "{name}: {}", text(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["max_channel_diff"], 0, "{name}");
    }
}
