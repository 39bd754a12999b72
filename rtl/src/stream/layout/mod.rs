//! Word layouts of the AXI4-Stream tops (`pixel-stream`, `textured-stream`, `gouraud-stream`,
//! `cubic-stream`, `angular-stream`, `fast-stream`, `quadric-stream`, `subdivision-stream`),
//! defined once.
//!
//! The set-up stream (`s_axis_*`, 32-bit words) carries *records*: a header word, then the
//! record's fields packed LSB first into 32-bit words (a field of up to 32 bits never
//! straddles two words; a wider one takes a word and the next one's low bits), `tlast` on the
//! record's last word. The fragment stream (`m_axis_*`, 64-bit `tdata` and the
//! fragment's 32-bit depth on `tuser`) carries one fragment, or one triangle end, per beat; a
//! two-lane top (`angular-stream`, `fast-stream`, `quadric-stream`) has one such stream per
//! lane (`m_axis_a_*`, `m_axis_b_*`), `subdivision-stream` one per sub-triangle lane
//! (`m_axis_l0_*` … `m_axis_l3_*`, without `tuser`).
//!
//! Everything that reads or writes these words comes from the tables here:
//! - the driver packs records with [`pack`] (`pipeline::lit::scene_words` and the other methods' packers), and reads fragments with
//!   [`unpack_fragment`];
//! - each top's word banks, field selects and fragment packing are its generated core, a
//!   whole file [`core_file`] writes and `rtl/build.rs` puts in `OUT_DIR`; the hand-written
//!   top (`rtl/src/stream/pixel_stream.rs` and the other seven: record reader, FIFOs, output
//!   registers) includes it as its `core`;
//! - `rtl/README.md`'s layout table is printed by [`markdown`] (checked by a test as well).
//!
//! Field names and widths are the wrapped top's input ports (`pixel-pipeline`'s,
//! `textured-pipeline`'s, `gouraud-raster`'s, `cubic-pipeline`'s, `angular-pipeline`'s, `fast-pipeline`'s,
//! `quadric-unit`'s, `subdivision-raster`'s), in its port order — the quadric's by name —
//! (checked against its port list by `testbenches/tests/pixel_stream.rs`, `textured_stream.rs`,
//! `gouraud_stream.rs`,
//! `cubic_stream.rs`, `span_stream.rs` and `subdivision_stream.rs`).
//!
//! Not a block: no ports, no latency (the hardware that reads these words is the stream tops',
//! whose headers give them).

mod codec;
mod codegen;
mod markdown;
mod tables;

pub use codec::*;
pub use codegen::*;
pub use markdown::*;
pub use tables::*;

#[cfg(test)]
mod tests {
    use super::*;
    use codec::mask64;
    use tables::f;

    #[test]
    fn records_pack_and_unpack() {
        for r in TOPS.iter().flat_map(|t| t.records()) {
            let values: Vec<u64> = r
                .fields
                .iter()
                .enumerate()
                .map(|(i, fl)| 0x9E37_79B9_7F4A_7C15u64.rotate_left(i as u32 * 7) & mask64(fl.bits))
                .collect();
            let words = pack(&r, &values);
            assert_eq!(words[0], r.code);
            assert_eq!(unpack(&r, &words[1..]), values);
        }
        assert_eq!(payload_words(&TRIANGLE), 26);
        assert_eq!(payload_words(&REGISTERS), 8);
        assert_eq!(payload_words(&TEXTURED_TRIANGLE), 50);
        assert_eq!(payload_words(&TEXTURED_REGISTERS), 7);
        assert_eq!(payload_words(&TEXEL), 2);
        assert_eq!(payload_words(&TEXTURED_LINE), 16);
        assert_eq!(payload_words(&GOURAUD_TRIANGLE), 22);
        assert_eq!(payload_words(&CUBIC_LINE), 11);
        assert_eq!(payload_words(&ANGULAR_LINE), 13);
        assert_eq!(payload_words(&SPAN_REGISTERS), 5);
        assert_eq!(payload_words(&FAST_LINE), 19);
        assert_eq!(payload_words(&QUADRIC_LINE), 4);
        assert_eq!(payload_words(&QUADRIC_TRIANGLE), 40);
        assert_eq!(payload_words(&SUBDIVISION_PARENT), 86);
    }

    /// Every record's payload fits the record reader's word count.
    #[test]
    fn records_fit_the_readers_count() {
        for top in TOPS {
            assert!(
                top.bank_words() < 1 << crate::stream::record_reader::INDEX_BITS,
                "{}: {} words",
                top.block,
                top.bank_words()
            );
        }
    }

    /// A four-lane top takes lane K's fragment fields from the wrapped top's `*_lK` ports (the
    /// one lane suffix), and its streams are `m_axis_lK_*` (AXI4-Stream's interface prefix).
    #[test]
    fn lane_suffixed_ports() {
        let t = SUBDIVISION_STREAM;
        assert_eq!(t.port("x", "_l2"), "x_l2");
        assert_eq!(t.port("pixel", "_l0"), "valid_l0");
        assert_eq!(StreamTop::stream("_l3"), "m_axis_l3");
        assert_eq!(ANGULAR_STREAM.port("pixel", "_b"), "valid_b");
        assert_eq!(ANGULAR_STREAM.port("y", "_b"), "y_out");
    }

    /// A field wider than 32 bits starts a word and ends in the next one's low bits, where
    /// the next field may follow; 64 bits take two whole words.
    #[test]
    fn wide_fields_take_two_words() {
        const R: Record = Record {
            name: "wide",
            code: 1,
            fields: &[f("a", 5), f("w", 48), f("b", 16), f("c", 64), f("d", 1)],
        };
        let at: Vec<(usize, u32, usize)> = place(&R)
            .iter()
            .map(|p| (p.word, p.offset, p.last_word()))
            .collect();
        assert_eq!(at, [(0, 0, 0), (1, 0, 2), (2, 16, 2), (3, 0, 4), (5, 0, 5)]);
        let v = [0x1F, 0xABCD_1234_5678, 0xBEEF, u64::MAX - 5, 1];
        let words = pack(&R, &v);
        assert_eq!(words[2..5], [0x1234_5678, 0xBEEF_ABCD, 0xFFFF_FFFA]);
        assert_eq!(unpack(&R, &words[1..]), v);
    }

    #[test]
    fn fragment_fields_do_not_overlap() {
        let mut used = 0u128;
        for pl in FRAGMENT {
            let m = ((1u128 << pl.bits) - 1) << pl.at();
            assert_eq!(used & m, 0, "{} overlaps", pl.name);
            assert!(pl.at() + pl.bits <= FRAGMENT_BITS);
            used |= m;
        }
        let v = [0xABC, 0x123, 1, 0x12, 0x34, 0x56];
        assert_eq!(unpack_fragment(pack_fragment(&v)), v);
    }
}
