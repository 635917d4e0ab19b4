# frozen_string_literal: true

# A plot or a render has a sharp file beside it, for screens of 2 device pixels to the CSS
# pixel (course/sharp.py): media/x.png and media/x-2x.png. This hook offers both on the
# picture's <img> by their widths, with the width the page shows it at,
#
#     <img srcset="/media/.../reach.png 910w, /media/.../reach-2x.png 1820w"
#          sizes="(max-width: 59.99rem) min(calc(100vw - 2rem), 910px),
#                 min(calc(100vw - 22rem), 910px, 63rem)" src="/media/.../reach.png" ...>
#
# so that the browser fetches the sharp one only where the plain one has fewer pixels than
# the screen shows: a laptop at 2x does, one at 1x does not; a phone with no phone variant
# to take (a render) does at 3x, and the sharp file, in 256 colours, weighs about what the
# plain one does. The widest column is 63rem (--wide in main.css, 1008 px),
# so a sharp file is at most 2016 px wide. The <img> keeps its src, width and height
# (lazy_images.rb): the picture takes the same space whichever file the browser fetches.
# Where the <img> sits in a <picture> with a phone variant (phone_figures.rb), the
# <source> still wins in narrow windows.
module Sw2simSite
  module SharpImages
    SUFFIX = "-2x"

    module_function

    def offer(html, site_root, baseurl)
      html.gsub(LazyImages::IMG) do |tag|
        src = tag[LazyImages::SRC, 1]
        next tag if tag =~ /\bsrcset=/i || !(sharp_src = sharp_variant(src))

        plain = LazyImages.size_of(LazyImages.local_file(src, site_root, baseurl))
        sharp = LazyImages.size_of(LazyImages.local_file(sharp_src, site_root, baseurl))
        next tag unless plain && sharp && sharp[0] > plain[0]

        tag.sub(/<img\b/i, %(<img srcset="#{src} #{plain[0]}w, #{sharp_src} #{sharp[0]}w" ) +
                           %(sizes="#{sizes(plain[0])}"))
      end
    end

    # How wide the page shows a picture `width` pixels wide: its own width, or the column's
    # where that is narrower (below 60rem the window less 2rem of margins; from 60rem less
    # the sidebar's and margins' 22rem too, and at most --wide).
    def sizes(width)
      "(max-width: 59.99rem) min(calc(100vw - 2rem), #{width}px), " \
        "min(calc(100vw - 22rem), #{width}px, 63rem)"
    end

    # The sharp file's address of a picture under /media/ (nil for any other image, and for
    # the variants themselves).
    def sharp_variant(src)
      return nil unless src

      path = src.split(/[?#]/).first
      return nil unless path.include?("/media/") && path =~ /\.png\z/i
      return nil if path =~ /(-2x|-phone|-phone-3x)\.png\z/i

      LazyImages.beside(src, SUFFIX)
    end
  end
end
