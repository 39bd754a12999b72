//! Packing and unpacking by the tables: a record's words from its field values and back, and
//! the fragment beat.
//!
//! Not a block: no ports, no latency (the stream tops' headers give theirs).

use super::tables::*;

/// The most payload words of any `pixel-stream` record (its word bank).
pub fn bank_words() -> usize {
    PIXEL_STREAM.bank_words()
}

/// The header word of `r`.
pub fn header(r: &Record) -> u32 {
    r.code
}

/// A record's words: header, then `values` (one per field, in field order; only the field's
/// low bits are kept) packed. `tlast` goes with the last word.
pub fn pack(r: &Record, values: &[u64]) -> Vec<u32> {
    assert_eq!(
        values.len(),
        r.fields.len(),
        "{}: one value per field",
        r.name
    );
    let placed = place(r);
    let mut words = vec![0u32; 1 + payload_words(r)];
    words[0] = header(r);
    for (pl, v) in placed.iter().zip(values) {
        let v = *v & mask64(pl.bits);
        words[1 + pl.word] |= (v << pl.offset) as u32;
        if pl.bits > 32 {
            words[2 + pl.word] |= (v >> 32) as u32;
        }
    }
    words
}

/// The low `bits` bits set.
pub(super) fn mask64(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// The inverse of [`pack`] for the payload (without the header).
pub fn unpack(r: &Record, payload: &[u32]) -> Vec<u64> {
    place(r)
        .iter()
        .map(|pl| {
            let mut v = (payload[pl.word] as u64) >> pl.offset;
            if pl.bits > 32 {
                v |= (payload[pl.word + 1] as u64) << 32;
            }
            v & mask64(pl.bits)
        })
        .collect()
}

/// A fragment beat's fields, in [`FRAGMENT`] order.
pub fn unpack_fragment(beat: u128) -> Vec<u64> {
    FRAGMENT
        .iter()
        .map(|pl| ((beat >> pl.at()) & ((1u128 << pl.bits) - 1)) as u64)
        .collect()
}

/// A fragment beat from field values in [`FRAGMENT`] order.
pub fn pack_fragment(values: &[u64]) -> u128 {
    FRAGMENT
        .iter()
        .zip(values)
        .map(|(pl, v)| ((*v as u128) & ((1u128 << pl.bits) - 1)) << pl.at())
        .fold(0, |a, b| a | b)
}
