"""FC telegrams byte for byte against telegrams computed by hand (docs/protocols/fc.md, spec/fc-protocol.md).

Each expected telegram below was worked out on paper: STX 02, LGE = data bytes + ADR + BCC, ADR, the data
big-endian, BCC = XOR of every byte before it (the running XOR is written next to it)."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from motiontool.comms.fc import telegram as fc
from motiontool.comms.fc.values import from_pwe, to_pwe
from motiontool.paramdb import database


def h(text: str) -> bytes:
    return bytes.fromhex(text)


# (telegram, bytes, how the BCC was computed)
TX_RX = [
    # read 32-60 KPROP (PNU 3260 = 0x0CBC, AK 1 -> PKE 0x1CBC) at address 1, format 1
    (fc.parameter(0x01, fc.AK_READ, 3260), h("02 0E 01 1C BC 0000 00000000 0000 0000 AD"),
     "02^0E=0C ^01=0D ^1C=11 ^BC=AD"),
    # the drive's answer: AK 2 (double word) value 30, status word 0x0003
    (fc.parameter(0x01, fc.AK_VALUE_DWORD, 3260, 30, pcd=(0x0003, 0)), h("02 0E 01 2C BC 0000 0000001E 0003 0000 80"),
     "02^0E=0C ^01=0D ^2C=21 ^BC=9D ^1E=83 ^03=80"),
    # the VLT 6000 design guide's example: write parameter 202 = 1000 in RAM and EEPROM (word, AK 14 -> PKE
    # 0xE0CA) — here to address 1 in format 2 (ADR 0x81)
    (fc.parameter(0x81, fc.AK_WRITE_WORD_EEPROM, 202, 1000), h("02 0E 81 E0 CA 0000 000003E8 0000 0000 4C"),
     "02^0E=0C ^81=8D ^E0=6D ^CA=A7 ^03=A4 ^E8=4C"),
    # refused (AK 7): illegal parameter number (fault 0) for PNU 4000 = 0xFA0
    (fc.parameter(0x01, fc.AK_REFUSED, 4000, 0), h("02 0E 01 7F A0 0000 00000000 0000 0000 D2"),
     "02^0E=0C ^01=0D ^7F=72 ^A0=D2"),
    # refused: upper or lower limit exceeded (fault 2) on 32-60
    (fc.parameter(0x01, fc.AK_REFUSED, 3260, 2), h("02 0E 01 7C BC 0000 00000002 0000 0000 CF"),
     "02^0E=0C ^01=0D ^7C=71 ^BC=CD ^02=CF"),
    # process block only: control word 0x047F, reference 0x03E8, address 5
    (fc.Telegram(0x05, None, 0, 0, (0x047F, 0x03E8)), h("02 06 05 04 7F 03 E8 91"),
     "02^06=04 ^05=01 ^04=05 ^7F=7A ^03=79 ^E8=91"),
    # text block (AK 15) on PNU 4095, IND 1, PWE 0x01030000, text "AB": LGE = 10 + 2
    (fc.text_telegram(0x01, fc.AK_TEXT, 4095, 1, 0x01030000, b"AB"), h("02 0C 01 FF FF 0001 01030000 41 42 0F"),
     "02^0C=0E ^01=0F ^FF=F0 ^FF=0F ^01=0E ^01=0F ^03=0C ^41=4D ^42=0F"),
    # broadcast write in format 1 (ADR bit 5): 32-60 = 50, double word (AK 3 -> PKE 0x3CBC)
    (fc.parameter(0x20, fc.AK_WRITE_DWORD, 3260, 50), h("02 0E 20 3C BC 0000 00000032 0000 0000 9E"),
     "02^0E=0C ^20=2C ^3C=10 ^BC=AC ^32=9E"),
]


@pytest.mark.parametrize("telegram,raw,how", TX_RX, ids=[t[2].split()[0] + f"-{i}" for i, t in enumerate(TX_RX)])
def test_telegrams_are_the_hand_computed_bytes(telegram, raw, how):
    assert fc.bcc(raw[:-1]) == raw[-1], how
    assert fc.encode(telegram) == raw
    assert fc.decode(raw) == telegram


def test_lge_is_data_plus_adr_plus_bcc():
    """fc-protocol.md: LGE 6 (4 data bytes), 14 (12 data bytes), 10 + n (text)."""
    assert fc.encode(fc.Telegram(1, None, 0, 0, (0, 0)))[1] == 6
    assert fc.encode(fc.parameter(1, fc.AK_READ, 1))[1] == 14
    assert fc.encode(fc.text_telegram(1, fc.AK_TEXT, 1, 0, 0, b"x" * 7))[1] == 17
    assert len(fc.encode(fc.text_telegram(1, fc.AK_TEXT, 1, 0, 0, b"x" * fc.MAX_TEXT))) == 257
    with pytest.raises(ValueError, match="at most 245"):
        fc.text_telegram(1, fc.AK_TEXT, 1, 0, 0, b"x" * 246)


def test_both_address_formats_and_broadcast():
    """ADR format 1: 1-31 in bits 0-4, bit 5 broadcast; format 2: bit 7 set, 1-126 in bits 0-6, 0 broadcast."""
    assert fc.encode_address(1) == 0x01
    assert fc.encode_address(31) == 0x1F
    assert fc.encode_address(32) == 0xA0            # above 31 only format 2 holds it
    assert fc.encode_address(1, fmt=2) == 0x81
    assert fc.encode_address(126) == 0xFE
    assert fc.encode_address(0, broadcast=True) == 0x20
    assert fc.encode_address(0, broadcast=True, fmt=2) == 0x80
    assert fc.decode_address(0x01) == (1, False, 1)
    assert fc.decode_address(0x20) == (0, True, 1)
    assert fc.decode_address(0x81) == (1, False, 2)
    assert fc.decode_address(0x80) == (0, True, 2)
    assert fc.decode_address(0xFE) == (126, False, 2)
    for bad, fmt in ((0, 1), (32, 1), (127, 2), (0, 2)):
        with pytest.raises(ValueError):
            fc.encode_address(bad, fmt=fmt)


def test_pke_splits_into_ak_and_pnu():
    t = fc.decode(h("02 0E 81 E0 CA 0000 000003E8 0000 0000 4C"))
    assert (t.ak, t.pnu, t.pwe, t.address, t.broadcast) == (14, 202, 1000, 1, False)
    with pytest.raises(ValueError, match="12 bits"):
        fc.parameter(1, fc.AK_READ, 4096)


def test_damaged_telegrams_name_the_byte():
    good = bytearray(h("02 0E 01 1C BC 0000 00000000 0000 0000 AD"))
    bad = bytearray(good)
    bad[4] ^= 0x01
    with pytest.raises(fc.TelegramError, match="byte 15: BCC 0xad, computed 0xac"):
        fc.decode(bytes(bad))
    with pytest.raises(fc.TelegramError, match="byte 0: 0x03 where STX"):
        fc.decode(b"\x03" + bytes(good[1:]))
    with pytest.raises(fc.TelegramError, match="byte 1: LGE 14 announces 16 bytes, got 15"):
        fc.decode(bytes(good[:-1]))
    with pytest.raises(fc.TelegramError, match="byte 1: LGE 3"):
        fc.decode(h("02 03 01 02 00"))
    with pytest.raises(fc.TelegramError, match="LGE 12 for AK 1"):
        fc.decode(fc.encode(fc.text_telegram(1, 1, 5, 0, 0, b"ab")))  # a text block needs AK 15


def test_eleven_bit_characters_with_even_parity():
    """8 data bits, even parity, 1 stop bit: 0x41 has two ones (parity 0), 0x01 one (parity 1)."""
    # written most significant first: stop 1, parity, data bits 7..0, start 0 (the line sends start first)
    assert fc.character(0x41) == 0b1_0_01000001_0
    assert fc.character(0x01) == 0b1_1_00000001_0
    assert fc.character(0xFF) == 0b1_0_11111111_0
    for byte in range(256):
        assert fc.from_character(fc.character(byte)) == byte
    with pytest.raises(fc.TelegramError, match="parity error"):
        fc.from_character(fc.character(0x41) ^ 1 << 3)   # one data bit flipped
    with pytest.raises(fc.TelegramError, match="framing"):
        fc.from_character(fc.character(0x41) & ~(1 << 10))
    assert fc.wire_time(16, 115200) == pytest.approx(16 * 11 / 115200)  # 1.53 ms, fc-protocol.md "Timing"


def test_reader_resynchronises_after_garbage_and_damage():
    a = fc.encode(fc.parameter(1, fc.AK_READ, 3260))
    b = fc.encode(fc.parameter(2, fc.AK_READ, 3261))
    damaged = bytearray(a)
    damaged[5] ^= 0xFF
    reader = fc.TelegramReader()
    found = reader.feed(b"\xff\x00" + bytes(damaged) + b + a[:5])
    assert [type(x).__name__ for x in found] == ["TelegramError", "TelegramError", "TelegramError", "Telegram"]
    assert found[-1].pnu == 3261
    assert reader.feed(a[5:])[-1].pnu == 3260


@given(st.binary(max_size=300))
def test_reader_never_raises_on_arbitrary_bytes(data):
    for item in fc.TelegramReader().feed(data):
        assert isinstance(item, (fc.Telegram, fc.TelegramError))


@given(st.integers(0, 15), st.integers(0, 4095), st.integers(0, 0xFFFF), st.integers(0, 0xFFFFFFFF),
       st.integers(1, 126), st.booleans())
def test_parameter_telegrams_round_trip(ak, pnu, ind, pwe, address, text):
    adr = fc.encode_address(address)
    t = fc.text_telegram(adr, 15, pnu, ind, pwe, b"t" * (ak % 5)) if text else \
        fc.parameter(adr, ak if ak != 15 else 1, pnu, pwe, ind, (ind, pnu))
    assert fc.decode(fc.encode(t)) == t


@given(st.sampled_from(list(database())), st.data())
def test_a_parameter_value_survives_its_pwe(p, data):
    """docs/protocols/fc.md "Parameters": words for the word types when the value fits, double words otherwise, two's
    complement for the Int types — whatever a slave sends, the master reads back the same value."""
    signed = p.data_type.startswith("Int")
    value = data.draw(st.integers(-2**31, 2**31 - 1) if signed else st.integers(0, 2**32 - 1))
    ak, pwe = to_pwe(p, value)
    assert from_pwe(p, pwe, word=ak == fc.AK_VALUE_WORD) == value
