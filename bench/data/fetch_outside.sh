#!/usr/bin/env bash
# Fetches the "outside" photographs for ddtup-bench's quality measurements from
# Debian 12 (bookworm) packages and crops them to 512 x 512 PNG files. No image
# is kept in the repository; OUTSIDE.md beside this script lists every file
# (package, path, licence, crop) and bench/README.md the measurements.
#
#   OUT/tuned/      13 photographs from python3-skimage: the set the team has
#                   tuned on (the "13 outside photographs" of bench/README.md)
#   OUT/heldout-a/  20 photographs from wallpaper and game packages, never
#   OUT/heldout-b/  20 used for tuning; the 40 in sorted name order,
#                   alternately a, b, a, b, ... (choose on one, report both)
#
# Usage: bash bench/data/fetch_outside.sh OUT [DEBDIR]
#   OUT     folder for the three sub-folders (their *.png files are replaced)
#   DEBDIR  optional folder that keeps the downloaded .deb files for the next
#           run (default: a temporary folder, removed at the end)
#
# Needs: apt-get and dpkg (Debian 12: `apt-get download` then `dpkg -x`,
# nothing is installed; an `apt-get update` first if apt has no lists), and
# Debian's python3 with numpy and OpenImageIO's binding (python3-numpy,
# python3-openimageio; not in scripts/setup: install them by hand). Set PYTHON
# to use another interpreter. Re-running gives byte-identical files; the script
# checks them against the SHA-256 sums recorded at its end (made with
# OpenImageIO 2.4.7.1, libjpeg-turbo 2.1.5, libpng 1.6.39, zlib 1.2.13,
# numpy 1.24.2).
#
# Held-out transformation (exact integer arithmetic, no resampling filter):
#   k = min(4, floor(min(W, H) / 512)), at least 2 (smaller sources are not used)
#   take the centred 512k x 512k square of the decoded 8-bit source,
#   x0 = floor((W - 512k) / 2), y0 = floor((H - 512k) / 2),
#   and average each k x k block of its sRGB-encoded values:
#   out = floor((sum + k*k/2) / (k*k)), written as 8-bit RGB PNG (grey sources
#   are repeated into R, G and B). The averaging evens out the source's JPEG
#   blocking and noise.
# Tuned transformation (as the set was first made, so the files stay the same):
#   the centred min(512, W, H) square of the source, no scaling, alpha dropped,
#   grey kept grey, 8-bit PNG.
set -euo pipefail

out=${1:?usage: fetch_outside.sh OUT [DEBDIR]}
py=${PYTHON:-/usr/bin/python3}
if ! command -v apt-get >/dev/null || ! command -v dpkg >/dev/null; then
  echo "fetch_outside: needs apt-get and dpkg (Debian 12)" >&2; exit 1
fi
"$py" -c 'import numpy, OpenImageIO' 2>/dev/null \
  || { echo "fetch_outside: $py cannot import numpy and OpenImageIO" \
            "(apt-get install python3-numpy python3-openimageio)" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
debs=${2:-$work/debs}
mkdir -p "$debs" "$out"
debs=$(cd "$debs" && pwd)
out=$(cd "$out" && pwd)

# Exact versions: another version may hold other pixels.
packages=(
  python3-skimage=0.19.3-8
  lomiri-wallpapers-16.04=20.04.0-2
  lomiri-wallpapers-20.04=20.04.0-2
  mate-backgrounds=1.26.0-1
  plasma-workspace-wallpapers=4:5.27.5-2
  palapeli-data=4:22.12.3-1
  sddm-theme-maldives=0.19.0-5
)
for pv in "${packages[@]}"; do
  name=${pv%%=*}; version=${pv#*=}
  deb=
  for f in "$debs/${name}"_*.deb; do
    [ -f "$f" ] && [ "$(dpkg-deb -f "$f" Version)" = "$version" ] && deb=$f
  done
  if [ -z "$deb" ]; then
    echo "fetch_outside: apt-get download $pv"
    # apt's messages (as root: "Download is performed unsandboxed") only on failure
    if ! (cd "$debs" && apt-get download -qq "$pv" 2>"$work/apt.err"); then
      cat "$work/apt.err" >&2
    fi
    for f in "$debs/${name}"_*.deb; do
      [ -f "$f" ] && [ "$(dpkg-deb -f "$f" Version)" = "$version" ] && deb=$f
    done
    [ -n "$deb" ] || { echo "fetch_outside: could not download $pv" >&2; exit 1; }
  fi
  dpkg -x "$deb" "$work/root"
done

mkdir -p "$out/tuned" "$out/heldout-a" "$out/heldout-b"
rm -f "$out/tuned/"*.png "$out/heldout-a/"*.png "$out/heldout-b/"*.png

"$py" - "$work/root" "$out" <<'EOF'
import os, sys
import numpy as np
import OpenImageIO as oiio

root, out = sys.argv[1], sys.argv[2]
SK = 'usr/lib/python3/dist-packages/skimage/data/'
LW = 'usr/share/backgrounds/'
MN = 'usr/share/backgrounds/mate/nature/'
KW = 'usr/share/wallpapers/%s/contents/images/2560x1600.jpg'
PL = 'usr/share/palapeli/collection/'

tuned = ['brick.png', 'cell.png', 'clock_motion.png', 'color.png', 'grass.png', 'gravel.png',
         'hubble_deep_field.jpg', 'ihc.png', 'moon.png', 'motorcycle_left.png', 'page.png',
         'retina.jpg', 'text.png']

heldout = {  # output name: path inside its package
    'aitzgorri': LW + 'aitzgorri_by_Aitzol_Berasategi.jpg',
    'bridge': LW + 'Bridge_by_Sander_Klootwijk.jpg',
    'dragonfly': LW + 'Dragonfly_by_Bolly.jpg',
    'free': LW + 'free_by_Peter_Nerlich.jpg',
    'friends': LW + 'friends_by_Aitzol_Berasategi.jpg',
    'greentock': LW + 'greentock_by_Peter_Nerlich.jpg',
    'life': LW + 'life_by_Aitzol_Berasategi.jpg',
    'picosdeeuropa': LW + 'picosdeeuropa_by_Aitzol_Berasategi.jpg',
    'picture_0b': LW + 'Picture_0B_by_freespace.jpg',
    'picture_1a': LW + 'Picture_1A_by_freespace.jpg',
    'seeding': LW + 'seeding_by_Clements_Engelhardt.jpg',
    'sunset': LW + 'sunset_by_Aitzol_Berasategi.jpg',
    'wine': LW + 'Wine_by_Jakkub_Mede.jpg',
    'kleiber': LW + 'Kleiber_by_Lukas_Baubkus.jpg',
    'aqua': MN + 'Aqua.jpg',
    'blinds': MN + 'Blinds.jpg',
    'dune': MN + 'Dune.jpg',
    'freshflower': MN + 'FreshFlower.jpg',
    'garden': MN + 'Garden.jpg',
    'greenmeadow': MN + 'GreenMeadow.jpg',
    'ladybird': MN + 'LadyBird.jpg',
    'raindrops': MN + 'RainDrops.jpg',
    'storm': MN + 'Storm.jpg',
    'twowings': MN + 'TwoWings.jpg',
    'wood': MN + 'Wood.jpg',
    'yellowflower': MN + 'YellowFlower.jpg',
    'bythewater': KW % 'BytheWater',
    'coldripple': KW % 'ColdRipple',
    'colorfulcups': KW % 'ColorfulCups',
    'darkesthour': KW % 'DarkestHour',
    'eveningglow': KW % 'EveningGlow',
    'fallenleaf': KW % 'FallenLeaf',
    'grey': KW % 'Grey',
    'kite': KW % 'Kite',
    'onestandsout': KW % 'OneStandsOut',
    'path': KW % 'Path',
    'summer_1am': KW % 'summer_1am',
    'honeybee': PL + 'european-honey-bee.jpg',
    'chameleon': PL + 'panther-chameleon-female.jpg',
    'maldives': 'usr/share/sddm/themes/maldives/background.jpg',
}

def read(rel, kind):
    buf = oiio.ImageBuf(os.path.join(root, rel))
    a = buf.get_pixels(kind)
    if a is None or buf.has_error:
        sys.exit('fetch_outside: %s: %s' % (rel, buf.geterror()))
    return a

def write(a, path, kind):
    h, w, c = a.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.UINT8))
    buf.set_pixels(oiio.ROI(), a if kind is None else a.astype(kind))
    if not buf.write(path):
        sys.exit('fetch_outside: %s: %s' % (path, buf.geterror()))

# Tuned: the centred min(512, W, H) square as float, written as 8 bits
# (v/255 converts back to v exactly), alpha dropped, channels otherwise kept.
for f in tuned:
    a = read(SK + f, oiio.FLOAT)
    h, w = a.shape[:2]
    if a.shape[2] == 4:
        a = a[:, :, :3]
    s = min(512, h, w); y, x = (h - s) // 2, (w - s) // 2
    write(np.ascontiguousarray(a[y:y + s, x:x + s]),
          os.path.join(out, 'tuned', os.path.splitext(f)[0] + '.png'), None)
    print('tuned     %-20s %5d x %-5d crop %d at (%d, %d)' % (f, w, h, s, x, y))

# Held-out: k x k area average of the centred 512k square, 8-bit RGB.
for i, name in enumerate(sorted(heldout)):
    half = 'heldout-a' if i % 2 == 0 else 'heldout-b'
    a = read(heldout[name], oiio.UINT8)
    h, w, c = a.shape
    if c == 1:
        a = np.repeat(a, 3, axis=2)
    a = a[:, :, :3]
    k = min(4, min(w, h) // 512)
    assert k >= 2, name
    s = 512 * k; x, y = (w - s) // 2, (h - s) // 2
    blocks = a[y:y + s, x:x + s].astype(np.uint32).reshape(512, k, 512, k, 3).sum(axis=(1, 3))
    write((blocks + (k * k) // 2) // (k * k), os.path.join(out, half, name + '.png'), np.uint8)
    print('%s %-20s %5d x %-5d 1/%d of %d at (%d, %d)' % (half, name, w, h, k, s, x, y))
EOF

# SHA-256 of every file as first made (2026-12-03). A mismatch most likely
# means another OpenImageIO/libpng/zlib writes the same pixels differently
# (compare pixels, e.g. `oiiotool --diff`), or another package version.
(cd "$out" && sha256sum -c --quiet) <<'EOF' && echo "fetch_outside: 53 files, all as recorded" \
  || echo "fetch_outside: WARNING: some files differ from the recorded sums (see above)" >&2
2c6e40f27603cd2f0c9c02fbf36796f48510c0c4e866b7cc8bbf0cbeb81f6d43  tuned/brick.png
4b8524d1db2491705cc1dd1b0f09547dc936662507dbc58c8fb3b84c6b8df811  tuned/cell.png
b9f05f1d3e915ec55e70337fad588ab8895dc84a59b5de98fe9b4fafdb97faf9  tuned/clock_motion.png
d438560bfaf82d8062d28c3a342ab9522aac5ee63da08c6f1ccb9debf9496572  tuned/color.png
1f96d0049eedd4332c23899ecf8f56acd1728fdb3aa2bb835244fea5f4e3add3  tuned/grass.png
baa552f5345ecdb084cbbd92cdb63f9414dafca3a71ff32849c04ec598a665e5  tuned/gravel.png
b8ca4975762cc47086a83b5ca2c88bb8d979990d75c28b6ab5710ce9406608b4  tuned/hubble_deep_field.png
d3ae87c0881caaaf83420064a9539d1ddbc7f6866157353b6939fd1d96f99d84  tuned/ihc.png
9b2774916c66ca8e6c7276538cad9c18c156495f78ddc3399ed9d4196176301a  tuned/moon.png
44bd7c9727f2e95ba3b2ae7accc7ca556d9dd6aa58f4e863b40e40d68ae39d95  tuned/motorcycle_left.png
fef2f2670444c6e43994b0a5492cd81c22db76a458af2d3271f3b1f46ac21a70  tuned/page.png
9d3d14e4c2b5d8f50ecd96878e4148edd605253c0341fea304271db5be278587  tuned/retina.png
d8bb0f226c756194055c22e9e1059869650e8c31d6f213f4b2c2a999e16908f0  tuned/text.png
77607461db2544b30dca414ba2f1fc4d93c162ab89becc3695b8337aae16d20c  heldout-a/aitzgorri.png
e2a5a21c5ad55438e2bec952e2c505104832043253b789f10f0517115af4d3a1  heldout-a/blinds.png
6d70bdf99a13b458c6bb5c6c9dba194a183e3a97ecb868106b05ba9372896f98  heldout-a/bythewater.png
c8276b56287854b49fb126045e7c30b4c3b36e0658eaaba9f90197b0d41495d2  heldout-a/coldripple.png
eafe380b8b977ac0c2047cbd169d8c196b20fb72c9f00ed0f60b442b0216367b  heldout-a/darkesthour.png
3685445ec63a982aae9f8d03eced6a3512bdf680877ab110574c663a23cafa0d  heldout-a/dune.png
ad9a197209ef325bb916b4129a7270d34afd2eeba8b5a849ed404e9c3ddd77bd  heldout-a/fallenleaf.png
6cd4c265dab5676b6efa30b11cd2dc6571fc0baca66376401f3dd0f4d50d3565  heldout-a/freshflower.png
714db5c55305f61696368abefd379a786e980ee8ff3645cdb8e26b8f47d16e15  heldout-a/garden.png
99cd9e95e367e9067da8ba25dcf6f86332de90ae497b5de72b61b89b9f252b37  heldout-a/greentock.png
afce5b6a99720569bd05c22751e109b583a89a18febcf0ffa20a3b9ef7d91af0  heldout-a/honeybee.png
24f32e5e2067d238360dfc79f025396908645127f1d37e12830b4a5f6a10ff4a  heldout-a/kleiber.png
9e0f671f8a807a2c24e25268b515be0a2b5a9132e0116a018b347845dd11f908  heldout-a/life.png
c712d95bf18522d5f5101a7ea46e2ff02ff80d685c911328fe9aa5f6687f0446  heldout-a/onestandsout.png
e73fa7a9d4c11187c2f4266079024a6f5c8d857cffe8e3d02ff2628161b859f1  heldout-a/picosdeeuropa.png
9092b6fddfcec0e6338dfaf26cbcf4041665527c2c23d295191382dfa3670f8b  heldout-a/picture_1a.png
21bcab3668d6cf8698466e163cdd7a52652999f32328cea736fffc6257135e2a  heldout-a/seeding.png
90f3849ea2c6253b9f4837beacec000a084598dbb3cf7c84dd7a6590101fa9c3  heldout-a/summer_1am.png
d11dd4b20cf3fec794a6136a8d89f5b0188437897236fa7b99c08588ec7b5b6d  heldout-a/twowings.png
fc815c6d101ee12e6d9a920acae3c5ef21835ebeb8dd2d919364e5b6dae56aa1  heldout-a/wood.png
ece80cf720b7b2263c9421a25dac9dfae9670246b4fc5335bf33ea450de3f47a  heldout-b/aqua.png
739691a7dc6fc422455cd155155f06ec4e2568bb03379e58217fd31e4f31bb49  heldout-b/bridge.png
ad78a9d4668bf30fb5fbaf26af00af2dea3fe04089f37f1981a2bf6d179d83b3  heldout-b/chameleon.png
5c4f506b62af97adb35d79546a0e9fdf7778d45a7e44faab21131ba4f25d251e  heldout-b/colorfulcups.png
a78ea76af208c7cceaa2df2265b42b69f80a5cb467df59319e741f6fab872047  heldout-b/dragonfly.png
a7ab3c45d5aea7e5f578531db476ae5c30d4af0650cd5ee6a5349f7ad9d88bc0  heldout-b/eveningglow.png
3370daa8d54fb67dfbaf1449de370dfa2bb81987b6b069cff2a5f2f248576c08  heldout-b/free.png
ec77145332dfd11d577cda35491c9473a8a9ee5b90375090b9e004bfda659a3f  heldout-b/friends.png
c44787a5f737e8e8fbe5501b66447084965bfc89bad6e8acf2f7e0b89d758ea2  heldout-b/greenmeadow.png
0161afd4b39c55467eb1effb3cae4a16be66ee855d76bf3063494bc4432c3b85  heldout-b/grey.png
a2aa64ee886c781d2b2abb4caff37f18c200a78a0e8e00205b0c59fe5c9a8a4c  heldout-b/kite.png
bc0c2f4181a602e20e0d9dfddfc1117ff2f707f56cf824e33d808cf184b2f102  heldout-b/ladybird.png
e2d52332874ef96695f7ee62c9275fefa9f84f5ed2e0b1804c49644dbe1577f0  heldout-b/maldives.png
849f56e15e82a2c20b77462a0f075e93f8bdc019953a23c814832ae7fc7ad377  heldout-b/path.png
7f8788564c6d94e02ff25456f7e198d138a04b70ed82551eda2f7bca3284d5c5  heldout-b/picture_0b.png
8b34c5c7c02b45c19bee4f7426f1435a72a6f212b1c4460cc15579e475569f93  heldout-b/raindrops.png
e50457ed58083aa08022ee0d42d0b5b8a504939b5d016adbf8f137d8e8701dce  heldout-b/storm.png
3c757234c60518f0e39119fb6d518000d2787241e06d012aa4af7e7f636e2b62  heldout-b/sunset.png
470fc268509c7c66c5d2f3fb9e3d0516f40627258b538d957f26be43905ae60b  heldout-b/wine.png
08906fe99210346bcc97e1e6a853263ff3d9dd24f9363b9e719d50799cf4b8b6  heldout-b/yellowflower.png
EOF
