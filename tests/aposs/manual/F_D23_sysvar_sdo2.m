// F_D23 — Enable/disable the second SDO server through SYSVAR (object 0x1201)
// Source: D:7339-7349 (MCO 305 Design Guide)
// Kind: fragment, already a valid statement sequence; nothing added.
// OCR repairs: none
// Note: "SD02" (digit zero) is kept as printed; it is a valid identifier either way.

SD02_txid = 0x680 + (get CANNR)
SD02_rxid = 0x100 + (get CANNR)
COB_NOT_VALID = 0x80000000
    // enable SD02
    sysvar[0x01120101] = SD02_txid
    sysvar[0x01120102] = SD02_rxid
    // disable SD02
    sysvar[0x01120101] = (SD02_txid | COB_NOT_VALID)
    sysvar[0x01120102] = (SD02_rxid | COB_NOT_VALID)
