import struct, zlib, array
def read(path):
    b = open(path, 'rb').read()
    assert b[:8] == b'CAVF32Z1', path
    w, h, c, bps = struct.unpack_from('<4I', b, 8)
    raw = zlib.decompress(b[32:])
    n = w * h * c
    if bps == 1:
        pal = struct.unpack_from('<256f', raw, 0)
        idx = raw[1024:1024 + n]
        px = [pal[i] for i in idx]
    else:
        # unshuffle
        un = bytearray(n * bps)
        for k in range(bps):
            un[k::bps] = raw[k * n:(k + 1) * n]
        px = list(struct.unpack('<%d%s' % (n, 'f' if bps == 4 else 'e'), bytes(un)))
    return w, h, c, px
