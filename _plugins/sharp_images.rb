# frozen_string_literal: true

# A plot has a sharp file beside it, for screens of 2 device pixels to the CSS pixel
# (course/sharp.py): media/x.png and media/x-2x.png. This hook offers both on the plot's
# <img>,
#
#     <img src="/media/.../reach.png" srcset="/media/.../reach.png 1x, /media/.../reach-2x.png 2x" ...>
#
# so that such a screen fetches the sharp one and any other the plain one. The sharp file
# is at most twice the widest column (1008 px) wide: for a plot wider than that, its
# density is less than 2 (2016 / 1560 = 1.292x), which is what the widest column shows.
# The <img> keeps its src, width and height (lazy_images.rb): the picture takes the same
# space whichever file the browser fetches. Where the <img> sits in a <picture> with a
# phone variant (phone_figures.rb), the <source> still wins in narrow windows.
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

        density = format("%.3f", sharp[0].to_f / plain[0]).sub(/\.?0+\z/, "")
        tag.sub(/<img\b/i, %(<img srcset="#{src} 1x, #{sharp_src} #{density}x"))
      end
    end

    # The sharp file's address of a plot under /media/ (nil for any other image, and for
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
