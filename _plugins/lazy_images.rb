# frozen_string_literal: true

# Two things every <img> of a rendered page needs to load well:
# - loading="lazy" when it does not say how to load, so long pages fetch figures as the
#   reader scrolls to them. It has to be in the HTML itself: a script setting it after
#   parsing comes too late, the fetch has started. An image written with its own
#   `loading` attribute (e.g. loading="eager") is left alone.
# - width and height, read from the file, when it has neither: the browser reserves the
#   figure's space before it arrives, so the page does not jump and images far down the
#   page are really far down (the CSS scales them with max-width and height: auto).
module Sw2simSite
  module LazyImages
    IMG_WITHOUT_LOADING = /<img\b(?![^>]*\bloading=)/i.freeze
    IMG = /<img\b[^>]*>/i.freeze
    SRC = /\bsrc="([^"]+)"/i.freeze
    # CSS pixels per unit, for SVG sizes given in absolute units.
    UNITS = { "" => 1.0, "px" => 1.0, "pt" => 96.0 / 72, "mm" => 96.0 / 25.4,
              "cm" => 96.0 / 2.54, "in" => 96.0 }.freeze

    module_function

    def mark(html, site_root, baseurl)
      html = html.gsub(IMG_WITHOUT_LOADING, '<img loading="lazy"')
      html.gsub(IMG) do |tag|
        next tag if tag =~ /\b(width|height)=/i || tag !~ SRC

        size = size_of(local_file(Regexp.last_match(1), site_root, baseurl))
        size ? tag.sub(/<img\b/i, %(<img width="#{size[0]}" height="#{size[1]}")) : tag
      end
    end

    def local_file(src, site_root, baseurl)
      return nil if src =~ %r{\A[a-z]+:|\A//}i

      path = src.split(/[?#]/).first
      path = path.delete_prefix(baseurl) unless baseurl.to_s.empty?
      File.join(site_root, path)
    end

    # The address (or file) `src` with `suffix` before its extension, keeping any ?query
    # or #anchor: the name of a variant kept beside a figure (x.png, x-2x.png).
    def beside(src, suffix)
      path, rest = src.split(/(?=[?#])/, 2)
      path.sub(/(\.\w+)\z/, "#{suffix}\\1") + rest.to_s
    end

    def size_of(file)
      return nil unless file && File.file?(file)

      case File.extname(file).downcase
      when ".png" then png_size(file)
      when ".svg" then svg_size(file)
      end
    end

    def png_size(file)
      head = File.binread(file, 24)
      return nil unless head && head.bytesize == 24 && head[12, 4] == "IHDR"

      head[16, 8].unpack("NN")
    end

    def svg_size(file)
      tag = File.read(file, 4096)[/<svg\b[^>]*>/m]
      return nil unless tag

      width, height = %w[width height].map { |a| length(tag[/\b#{a}="([^"]+)"/, 1]) }
      if !(width && height) && (box = tag[/\bviewBox="([^"]+)"/, 1])
        width, height = box.split(/[\s,]+/).map(&:to_f)[2, 2]
      end
      width && height && width.positive? && height.positive? ? [width.round, height.round] : nil
    end

    def length(value)
      match = value.to_s.strip.match(/\A([\d.]+)\s*(px|pt|mm|cm|in)?\z/)
      match && match[1].to_f * UNITS.fetch(match[2].to_s)
    end
  end
end
