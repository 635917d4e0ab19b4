# frozen_string_literal: true

# What every <img> of a rendered page gets, in one hook so that the order is seen:
# - a phone variant in a <picture> where the figure has one (phone_figures.rb);
# - the sharp file for 2x screens in its srcset where the picture has one (sharp_images.rb);
# - loading="lazy", width and height (lazy_images.rb).
# Each reads only an <img>'s src and adds nothing another looks for. After rendering, the
# src attributes carry the baseurl (site_links.rb), and so do the variants' addresses made
# from them.
Jekyll::Hooks.register [:pages, :documents], :post_render do |page|
  next unless page.output_ext == ".html"

  root = page.site.source
  baseurl = page.site.config["baseurl"]
  html = Sw2simSite::PhoneFigures.serve(page.output, root, baseurl)
  html = Sw2simSite::SharpImages.offer(html, root, baseurl)
  page.output = Sw2simSite::LazyImages.mark(html, root, baseurl)
end
