// The text of rtimg --help; docs/rtimg.1 and docs/rtimg.md say the same at length.
#include "rtimg.h"

namespace rtimg {

const char* usage_text() {
    return R"(usage: rtimg diff [--tolerance T] [--max-fraction F] [-o DIFF] A B
       rtimg merge PIECES... -o FULL
       rtimg convert [--bits 8|16] [--gamma G] [--plain] IN OUT
       rtimg info FILE

Compares, merges, converts and describes images: PPM and PGM (P6, P5, P3, P2;
8 or 16 bits), PNG (any bit depth and colour type) and PFM. Formats are told
from the files' contents when reading, and from the extension when writing.

commands:
  diff      prints the size, the largest difference, how many pixels differ by
            more than T, mean absolute error, RMSE and PSNR (all in 8-bit levels
            of red, green and blue); exit 0 when the share of differing pixels
            is at most F, 1 when it is more or the sizes differ, 2 on error
  merge     puts regions rendered with rt --region back together: checks that
            they tile the full image, and writes it as a whole render would
  convert   writes IN in the format OUT's extension names (.ppm, .pgm, .png,
            .pfm), as RGB; metadata is kept where the format has a place
  info      the format, size, bit depth, region, what made the image and each
            channel's minimum, maximum and mean

options:
      --tolerance T     diff: a pixel differs when a component is more than T
                        levels (of 255) away (default 0)
      --max-fraction F  diff: fail when more than this share (0 to 1) of the
                        pixels differ (default 0)
  -o, --output FILE     diff: write a heat map of the differences (PPM or PNG);
                        merge: the full image (required)
      --bits N          convert: 8 or 16 bits per sample (default: the input's;
                        8 from PFM)
      --gamma G         convert: encode the input's values, taken as linear, as
                        linear (default), srgb or c^(1/G)
      --plain           convert: write plain-text PPM (P3)
  -h, --help            print this help and exit
  -V, --version         print the version and exit

exit status: 0 success, 1 error (diff: the images differ too much or their sizes
differ), 2 usage error (diff: any error)
)";
}

}  // namespace rtimg
