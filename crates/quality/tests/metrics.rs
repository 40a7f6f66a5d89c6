//! The metrics against known values.

use steadyray_quality::{Rgb8Image, compare, flip, flip_at, psnr, ssim};

/// A 64×48 test card: integer patterns in every channel.
fn card() -> Rgb8Image {
    Rgb8Image::from_fn(64, 48, |x, y| {
        let (x, y) = (x as i32, y as i32);
        [
            (x * 7 + y * 13) % 256,
            (x * x + 3 * y) % 256,
            ((x ^ y) * 5) % 256,
        ]
        .map(|v| v as u8)
    })
}

/// The card with a fixed ±20 pattern added (clamped) and a 16×16 square inverted.
fn distorted() -> Rgb8Image {
    let c = card();
    Rgb8Image::from_fn(64, 48, |x, y| {
        let n = ((x * 31 + y * 17) % 41) as i32 - 20;
        let p = c
            .pixel(x, y)
            .map(|v| (i32::from(v) + n).clamp(0, 255) as u8);
        if (20..36).contains(&x) && (10..26).contains(&y) {
            p.map(|v| 255 - v)
        } else {
            p
        }
    })
}

#[test]
fn flip_of_an_image_against_itself_is_zero() {
    let m = flip(&card(), &card()).unwrap();
    assert_eq!(m.mean(), 0.0);
    assert!(m.values().iter().all(|&v| v == 0.0));
}

/// The value NVIDIA's own Python package gives for the same pair: `flip-evaluator` 1.7 from
/// PyPI (`flip_evaluator.evaluate(ref, test, "LDR")` on the same arrays / 255, its default
/// 67.02 pixels per degree) returns a mean of 0.16014868.
#[test]
fn flip_of_a_known_distortion_matches_the_reference_implementation() {
    let mean = flip(&card(), &distorted()).unwrap().mean();
    assert!((mean - 0.160_148_68).abs() < 1e-3, "mean FLIP {mean}");
}

/// Pixels seen larger (fewer per degree: a small image filling a display) show the same noise
/// more; seen from farther away (more per degree) less. At FLIP's default the result is
/// [`flip`]'s.
#[test]
fn flip_depends_on_the_viewing_condition() {
    let (c, d) = (card(), distorted());
    let default = flip_at(&c, &d, steadyray_quality::flip::PIXELS_PER_DEGREE).unwrap();
    assert_eq!(default.mean(), flip(&c, &d).unwrap().mean());
    let large = flip_at(&c, &d, 12.6).unwrap().mean();
    let far = flip_at(&c, &d, 200.0).unwrap().mean();
    assert!(
        large > 1.5 * default.mean(),
        "{large} vs {}",
        default.mean()
    );
    assert!(far < 0.9 * default.mean(), "{far} vs {}", default.mean());
}

#[test]
fn psnr_matches_the_formula() {
    let a = Rgb8Image::from_fn(8, 8, |_, _| [100, 100, 100]);
    // Every value off by 10: MSE 100, PSNR 10·log10(255²/100).
    let b = Rgb8Image::from_fn(8, 8, |_, _| [110, 90, 110]);
    let expected = 10.0 * (255.0f64 * 255.0 / 100.0).log10();
    assert!((psnr(&a, &b).unwrap() - expected).abs() < 1e-12);
    assert!(psnr(&a, &a).unwrap().is_infinite());
    // One value off by 255 among 3·4 values: MSE 255²/12.
    let c = Rgb8Image::from_fn(2, 2, |x, y| if x + y == 0 { [255, 0, 0] } else { [0; 3] });
    let d = Rgb8Image::from_fn(2, 2, |_, _| [0; 3]);
    assert!((psnr(&c, &d).unwrap() - 10.0 * 12f64.log10()).abs() < 1e-12);
}

#[test]
fn ssim_is_one_for_identical_images_and_falls_with_distortion() {
    let s_same = ssim(&card(), &card()).unwrap();
    assert!((s_same - 1.0).abs() < 1e-12, "{s_same}");
    let s_bad = ssim(&card(), &distorted()).unwrap();
    assert!(s_bad < 0.9, "{s_bad}");
    // A flat shift of brightness keeps the structure: SSIM stays high.
    let brighter = Rgb8Image::from_fn(64, 48, |x, y| {
        card().pixel(x, y).map(|v| v.saturating_add(5))
    });
    let s_shift = ssim(&card(), &brighter).unwrap();
    assert!(s_shift > s_bad && s_shift > 0.9, "{s_shift}");
}

#[test]
fn more_distortion_is_more_flip() {
    let c = card();
    let noisy = |amp: i32| {
        Rgb8Image::from_fn(64, 48, |x, y| {
            let n = ((x * 31 + y * 17) % 41) as i32 - 20;
            c.pixel(x, y)
                .map(|v| (i32::from(v) + n * amp / 20).clamp(0, 255) as u8)
        })
    };
    let f = |amp| compare(&c, &noisy(amp)).unwrap().flip;
    assert!(0.0 < f(2) && f(2) < f(8) && f(8) < f(20));
}

#[test]
fn sizes_must_match() {
    let small = Rgb8Image::from_fn(4, 4, |_, _| [0; 3]);
    assert!(flip(&card(), &small).is_err());
    assert!(psnr(&card(), &small).is_err());
    assert!(ssim(&card(), &small).is_err());
    // A reduced-resolution frame is compared after upscaling.
    let up = small.resize_bilinear(64, 48);
    assert!(compare(&card(), &up).is_ok());
}

#[test]
fn the_error_map_has_the_image_size() {
    let map = flip(&card(), &distorted()).unwrap();
    let magma = map.to_magma();
    assert_eq!((magma.width(), magma.height()), (64, 48));
    // Zero error is magma's black end.
    let zero = flip(&card(), &card()).unwrap().to_magma();
    assert!(
        zero.pixel(0, 0).iter().all(|&v| v < 10),
        "{:?}",
        zero.pixel(0, 0)
    );
}
