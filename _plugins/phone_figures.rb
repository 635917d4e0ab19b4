# frozen_string_literal: true

# A figure with lettering has a phone variant beside it, drawn by the same code for a
# narrow column (course/phone.py): media/x.png and media/x-phone.png, media/y.svg and
# media/y-phone.svg. Where the pages' text column is narrower than 640 px, the figure laid
# out for 736 px would have its lettering under 9 px high; there the phone variant is
# shown instead. Page authors write the figure as any image,
#
#     ![Knuckle angles against the centre angle](/media/practice-5/knuckle_angles.png)
#
# and this hook turns every <img> whose file has a phone variant into
#
#     <picture class="figure-picture">
#       <source media="(max-width: 41.99rem), ..."
#               srcset="/media/.../knuckle_angles-phone.png 720w, /media/.../knuckle_angles-phone-3x.png 1080w"
#               sizes="(max-width: 59.99rem) calc(100vw - 2rem), calc(100vw - 22rem)"
#               width="720" height="1080">
#       <img src="/media/.../knuckle_angles.png" alt="..." width="1560" height="598" ...>
#     </picture>
#
# A plot's phone variant has two files, for screens of 2 and of 3 device pixels to the CSS
# pixel (course/plotting.py): the srcset offers both by their widths, and `sizes` says how
# wide the column is, so that the browser fetches the one the screen needs. A drawing's
# (an SVG) is one file. The <img> keeps everything it had: its alt text, its src (the
# figure as wider windows show it, and what the enlarged view opens: assets/js/site.js)
# and the size lazy_images.rb reads from its file; the <source> carries the phone
# variant's own size, so that the browser reserves the right space before the picture
# arrives.
module Sw2simSite
  module PhoneFigures
    SUFFIX = "-phone"
    DENSE_SUFFIX = "-3x"
    # Windows whose text column is narrower than 640 px (assets/css/main.css): below 60rem
    # the column is the window less 2rem of margins; from 60rem the sidebar and the page's
    # margins take 22rem, so the column is narrower than 640 px up to 62rem.
    NARROW = "(max-width: 41.99rem), (min-width: 60rem) and (max-width: 61.99rem)"
    # The column's width in those windows: the window less the margins, and from 60rem less
    # the sidebar too.
    COLUMN = "(max-width: 59.99rem) calc(100vw - 2rem), calc(100vw - 22rem)"

    module_function

    def serve(html, site_root, baseurl)
      html.gsub(LazyImages::IMG) do |tag|
        src = tag[LazyImages::SRC, 1]
        phone_src = src && phone_variant(src)
        file = phone_src && LazyImages.local_file(phone_src, site_root, baseurl)
        next tag unless file && File.file?(file)

        size = LazyImages.size_of(file)
        dimensions = size ? %( width="#{size[0]}" height="#{size[1]}") : ""
        %(<picture class="figure-picture"><source media="#{NARROW}" #{candidates(phone_src, file, size)}) +
          "#{dimensions}>#{tag}</picture>"
      end
    end

    # The srcset (and sizes) of a phone variant: its one file, or with its file for screens
    # of 3 pixels to the CSS pixel beside it, both by their widths.
    def candidates(phone_src, file, size)
      dense_file = dense_variant(file)
      dense_size = size && dense_file && File.file?(dense_file) && LazyImages.size_of(dense_file)
      return %(srcset="#{phone_src}") unless dense_size

      %(srcset="#{phone_src} #{size[0]}w, #{dense_variant(phone_src)} #{dense_size[0]}w" sizes="#{COLUMN}")
    end

    # The address (or file) of the dense file beside a phone variant's PNG (nil for an SVG).
    def dense_variant(phone)
      phone.split(/[?#]/).first =~ /\.png\z/i ? LazyImages.beside(phone, DENSE_SUFFIX) : nil
    end

    # The phone variant's address of a figure under /media/ (nil for any other image).
    def phone_variant(src)
      path = src.split(/[?#]/).first
      return nil unless path.include?("/media/") && path =~ /\.(png|svg)\z/i
      return nil if path.end_with?("#{SUFFIX}.png", "#{SUFFIX}.svg")

      LazyImages.beside(src, SUFFIX)
    end
  end
end
