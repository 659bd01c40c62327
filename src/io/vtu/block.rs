//! The binary blocks of VTK XML files: a header of `UInt32` or `UInt64` sizes, then the data,
//! raw or zlib-compressed in blocks, stored as raw bytes (appended `raw` data) or in base64
//! (inline `binary` arrays and appended `base64` data).
//!
//! Layout (VTK's file-format documentation): uncompressed, the header is one size, the byte
//! count of the data; compressed, it is `[number of blocks, block size, size of the last
//! block, compressed size of each block]` and the blocks follow, each a zlib stream. In base64
//! the header may be encoded on its own or in one stream with the data (writers differ; VTK
//! encodes a compressed header on its own): both are read.

use std::io::{Read, Write};

use base64::engine::general_purpose::STANDARD;
use base64::Engine;

use crate::error::{Error, Result};

/// Uncompressed size of the blocks the writer compresses (VTK's default).
const BLOCK_SIZE: usize = 1 << 15;

/// How the blocks of a file are stored: the header's integer width and byte order, and
/// whether the data is zlib-compressed.
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    /// Bytes of one header value: 4 (`UInt32`) or 8 (`UInt64`).
    pub header_bytes: usize,
    /// `byte_order="BigEndian"`.
    pub big_endian: bool,
    /// `compressor="vtkZLibDataCompressor"`.
    pub zlib: bool,
}

/// Where a block's bytes are: raw bytes, or base64 text (whitespace removed).
#[derive(Clone, Copy)]
pub enum Source<'a> {
    /// Raw appended data, from the block's offset on.
    Raw(&'a [u8]),
    /// Base64 text, from the block's start on.
    Base64(&'a [u8]),
}

impl Layout {
    /// The header value at `i` of `bytes`.
    fn value(&self, bytes: &[u8], i: usize) -> Result<usize> {
        let h = self.header_bytes;
        let chunk = bytes
            .get(i * h..(i + 1) * h)
            .ok_or_else(|| Error::io("a binary block ends inside its header"))?;
        let mut word = [0u8; 8];
        if self.big_endian {
            word[8 - h..].copy_from_slice(chunk);
            usize::try_from(u64::from_be_bytes(word))
        } else {
            word[..h].copy_from_slice(chunk);
            usize::try_from(u64::from_le_bytes(word))
        }
        .map_err(|_| Error::io("a binary block's size does not fit in memory"))
    }

    /// Length in bytes of the header whose first bytes (at least `3 × header_bytes` when
    /// compressed) are `start`.
    fn header_len(&self, start: &[u8]) -> Result<usize> {
        if !self.zlib {
            return Ok(self.header_bytes);
        }
        let blocks = self.value(start, 0)?;
        blocks
            .checked_add(3)
            .and_then(|n| n.checked_mul(self.header_bytes))
            .ok_or_else(|| Error::io("a compressed block's header is too large"))
    }

    /// Reads one block from `source` and returns its data, uncompressed; `expected` is the
    /// data's byte count the array's attributes call for.
    pub fn read(&self, source: Source<'_>, expected: usize) -> Result<Vec<u8>> {
        let (header, payload) = match source {
            Source::Raw(bytes) => {
                let len = self.header_len(bytes)?;
                let header = bytes
                    .get(..len)
                    .ok_or_else(|| Error::io("a binary block ends inside its header"))?;
                let size = self.payload_size(header)?;
                let payload = bytes
                    .get(len..len.saturating_add(size))
                    .ok_or_else(|| Error::io("a binary block ends before its data"))?;
                (header.to_vec(), payload.to_vec())
            }
            Source::Base64(text) => self.split_base64(text)?,
        };
        self.unpack(&header, payload, expected)
    }

    /// Byte count of the (possibly compressed) data a header announces.
    fn payload_size(&self, header: &[u8]) -> Result<usize> {
        if !self.zlib {
            return self.value(header, 0);
        }
        let blocks = self.value(header, 0)?;
        (0..blocks).try_fold(0usize, |sum, b| {
            sum.checked_add(self.value(header, 3 + b)?)
                .ok_or_else(|| Error::io("a compressed block is too large"))
        })
    }

    /// The header and data bytes of a base64 block, whether the header was encoded on its own
    /// or in one stream with the data.
    fn split_base64(&self, text: &[u8]) -> Result<(Vec<u8>, Vec<u8>)> {
        let decode = |t: &[u8]| {
            STANDARD
                .decode(t)
                .map_err(|e| Error::io(format!("bad base64 data: {e}")))
        };
        let slice = |from: usize, to: usize| {
            text.get(from..to)
                .ok_or_else(|| Error::io("base64 data ends before its block does"))
        };
        // The first three values fill whole base64 groups in both layouts.
        let peek_len = if self.zlib { 3 } else { 1 } * self.header_bytes;
        let peek = decode(slice(0, chars(peek_len)?.min(text.len()))?)?;
        let header_len = self.header_len(&peek)?;
        let group = chars(header_len)?;
        let separate = header_len % 3 != 0 && text.get(group - 1) == Some(&b'=');
        let (header, data) = if separate {
            let header = decode(slice(0, group)?)?;
            let size = self.payload_size(&header)?;
            let data = decode(slice(group, group.saturating_add(chars(size)?))?)?;
            (header, at_least(data, size)?)
        } else {
            let whole_header = at_least(decode(slice(0, group)?)?, header_len)?;
            let header = whole_header[..header_len].to_vec();
            let size = self.payload_size(&header)?;
            let total = header_len
                .checked_add(size)
                .ok_or_else(|| Error::io("a binary block is too large"))?;
            let mut all = at_least(decode(slice(0, chars(total)?)?)?, total)?;
            let data = all.split_off(header_len);
            (header, data)
        };
        Ok((header, data))
    }

    /// The data of a block from its header and payload, inflated when compressed.
    fn unpack(&self, header: &[u8], payload: Vec<u8>, expected: usize) -> Result<Vec<u8>> {
        let mismatch = |got: usize| {
            Error::io(format!(
                "a binary block holds {got} bytes, the array's size calls for {expected}"
            ))
        };
        if !self.zlib {
            return if payload.len() == expected {
                Ok(payload)
            } else {
                Err(mismatch(payload.len()))
            };
        }
        let blocks = self.value(header, 0)?;
        let block_size = self.value(header, 1)?;
        let last = self.value(header, 2)?;
        let size_of = |b: usize| {
            if b + 1 == blocks && last != 0 {
                last
            } else {
                block_size
            }
        };
        let total = (0..blocks).fold(0usize, |s, b| s.saturating_add(size_of(b)));
        if total != expected {
            return Err(mismatch(total));
        }
        // Each block's size is checked against what its compressed bytes can hold before
        // anything is allocated, and the allocation itself may fail with an error: a header
        // may claim any size.
        let mut chunks = Vec::with_capacity(blocks.min(payload.len()));
        let mut at = 0usize;
        for b in 0..blocks {
            let compressed = self.value(header, 3 + b)?;
            let chunk = at
                .checked_add(compressed)
                .and_then(|end| payload.get(at..end))
                .ok_or_else(|| Error::io(format!("compressed block {b} ends past the data")))?;
            if size_of(b) / MAX_DEFLATE_RATIO > compressed {
                return Err(Error::io(format!(
                    "compressed block {b} of {compressed} bytes cannot inflate to the {} bytes its header says",
                    size_of(b)
                )));
            }
            chunks.push(chunk);
            at += compressed;
        }
        let mut out = Vec::new();
        out.try_reserve_exact(total)
            .map_err(|_| Error::io(format!("the block's {total} bytes cannot be allocated")))?;
        out.resize(total, 0);
        let mut start = 0;
        for (b, chunk) in chunks.into_iter().enumerate() {
            let end = start + size_of(b);
            inflate(chunk, &mut out[start..end])
                .map_err(|e| Error::io(format!("compressed block {b}: {e}")))?;
            start = end;
        }
        Ok(out)
    }
}

/// The most a deflate stream inflates by (a byte per 1032 is zlib's limit, with some room).
const MAX_DEFLATE_RATIO: usize = 1100;

/// Characters of the base64 text of `bytes` bytes.
fn chars(bytes: usize) -> Result<usize> {
    bytes
        .div_ceil(3)
        .checked_mul(4)
        .ok_or_else(|| Error::io("a binary block is too large"))
}

/// `data`, which must hold at least `len` bytes, cut to `len`.
fn at_least(mut data: Vec<u8>, len: usize) -> Result<Vec<u8>> {
    if data.len() < len {
        return Err(Error::io("base64 data ends before its block does"));
    }
    data.truncate(len);
    Ok(data)
}

/// Inflates the zlib stream `chunk` into `out`, which it must fill exactly.
fn inflate(chunk: &[u8], out: &mut [u8]) -> std::result::Result<(), String> {
    let mut decoder = flate2::read::ZlibDecoder::new(chunk);
    decoder.read_exact(out).map_err(|e| match e.kind() {
        std::io::ErrorKind::UnexpectedEof => {
            format!(
                "inflates to fewer bytes than the {} its header says",
                out.len()
            )
        }
        _ => e.to_string(),
    })?;
    let mut more = [0u8; 1];
    match decoder.read(&mut more) {
        Ok(0) => Ok(()),
        Ok(_) => Err(format!(
            "inflates to more than the {} bytes its header says",
            out.len()
        )),
        Err(e) => Err(e.to_string()),
    }
}

/// One block in the layout the writer uses (little-endian `UInt64` header; zlib blocks of
/// 32 KiB when `zlib`): header and data, kept apart so that base64 can encode them apart.
pub fn pack(data: &[u8], zlib: bool) -> Result<(Vec<u8>, Vec<u8>)> {
    let word = |v: usize| (v as u64).to_le_bytes();
    if !zlib {
        return Ok((word(data.len()).to_vec(), data.to_vec()));
    }
    let chunks: Vec<&[u8]> = data.chunks(BLOCK_SIZE).collect();
    let mut header = Vec::new();
    header.extend(word(chunks.len()));
    header.extend(word(BLOCK_SIZE));
    header.extend(word(chunks.last().map_or(0, |c| c.len())));
    let mut payload = Vec::new();
    for chunk in chunks {
        let mut encoder =
            flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        encoder
            .write_all(chunk)
            .and_then(|_| encoder.finish())
            .map(|c| {
                header.extend(word(c.len()));
                payload.extend(c);
            })
            .map_err(|e| Error::io(format!("zlib compression failed: {e}")))?;
    }
    Ok((header, payload))
}

/// Base64 text of a block as the writer stores it: compressed, the header encoded on its own
/// (as VTK does), else header and data in one stream (as VTK and meshio do).
pub fn base64(header: &[u8], payload: &[u8], zlib: bool) -> String {
    if zlib {
        STANDARD.encode(header) + &STANDARD.encode(payload)
    } else {
        STANDARD.encode([header, payload].concat())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(zlib: bool) -> Layout {
        Layout {
            header_bytes: 8,
            big_endian: false,
            zlib,
        }
    }

    #[test]
    fn blocks_round_trip_in_every_storage() {
        let data: Vec<u8> = (0..100_000u32)
            .flat_map(|i| (i % 251).to_le_bytes())
            .collect();
        for zlib in [false, true] {
            let (header, payload) = pack(&data, zlib).unwrap();
            let raw = [header.clone(), payload.clone()].concat();
            let l = layout(zlib);
            assert_eq!(l.read(Source::Raw(&raw), data.len()).unwrap(), data);
            let text = base64(&header, &payload, zlib);
            assert_eq!(
                l.read(Source::Base64(text.as_bytes()), data.len()).unwrap(),
                data
            );
            // The other base64 layout: the header on its own when uncompressed, one stream
            // when compressed.
            let other = if zlib {
                STANDARD.encode(&raw)
            } else {
                STANDARD.encode(&header) + &STANDARD.encode(&payload)
            };
            assert_eq!(
                l.read(Source::Base64(other.as_bytes()), data.len())
                    .unwrap(),
                data
            );
            let e = l.read(Source::Raw(&raw), data.len() + 1).unwrap_err();
            assert!(e.message.contains("calls for"), "{}", e.message);
            let e = l
                .read(Source::Raw(&raw[..raw.len() - 1]), data.len())
                .unwrap_err();
            assert!(e.message.contains("ends"), "{}", e.message);
        }
    }
}
